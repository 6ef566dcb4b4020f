#pragma once
// DDS Security for PeNa participants (docs/security.md, "DDS Security"): the files of one
// identity as deploy/security/make-identities.sh writes them, their checks, and the Fast DDS
// participant properties that enable the builtin plugins (PKI-DH, Access-Permissions,
// AES-GCM-GMAC).

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pena::services {

// One participant's identity and the mission's rules.
struct SecurityFiles {
  std::filesystem::path identity_ca;     // the mission's identity CA certificate (PEM)
  std::filesystem::path certificate;     // this identity's certificate, signed by identity_ca
  std::filesystem::path private_key;     // its private key (PEM, unencrypted)
  std::filesystem::path permissions_ca;  // the permissions CA certificate (PEM)
  std::filesystem::path governance;      // the domain rules, S/MIME-signed by permissions_ca
  std::filesystem::path permissions;     // this identity's grants, S/MIME-signed by permissions_ca
  std::filesystem::path identity_crl;    // the identity CA's revocation list (PEM); empty: none
};

// The files of the identity directory `dir` (identity_ca.pem, cert.pem, key.pem,
// permissions_ca.pem, governance.p7s, permissions.p7s; identity_crl.pem if present).
SecurityFiles SecurityFilesIn(const std::filesystem::path& dir);

// Checks that every file is readable and what it should be: PEM certificates, a certificate
// signed by the identity CA, valid now and not on its revocation list, a private key that
// belongs to it, governance and permissions whose S/MIME signature verifies against the
// permissions CA. Throws DdsError
// naming the file and what is wrong with it.
struct CheckedIdentity {
  std::string subject;      // the certificate's subject, RFC 2253 ("CN=ff1,OU=entity,O=PeNa")
  std::string common_name;  // its CN: an entity's id, "fusion", an operator's id
};
CheckedIdentity CheckSecurityFiles(const SecurityFiles& files);

// The DomainParticipantQos properties that enable DDS Security with `files`.
std::vector<std::pair<std::string, std::string>> SecurityProperties(const SecurityFiles& files);

// The files named by security properties already present (from an XML profile), if the
// authentication plugin is set; "file:" URIs only (a property that names something else is an
// error).
std::optional<SecurityFiles> SecurityFilesFromProperties(
    const std::vector<std::pair<std::string, std::string>>& properties);

}  // namespace pena::services
