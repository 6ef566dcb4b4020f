#include "dds_security.hpp"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>

#include <fstream>
#include <memory>
#include <sstream>

#include "dds_participant.hpp"

namespace pena::services {
namespace {

const char* const kAuthPlugin = "dds.sec.auth.plugin";
const char* const kIdentityCa = "dds.sec.auth.builtin.PKI-DH.identity_ca";
const char* const kCertificate = "dds.sec.auth.builtin.PKI-DH.identity_certificate";
const char* const kIdentityCrl = "dds.sec.auth.builtin.PKI-DH.identity_crl";
const char* const kPrivateKey = "dds.sec.auth.builtin.PKI-DH.private_key";
const char* const kAccessPlugin = "dds.sec.access.plugin";
const char* const kPermissionsCa = "dds.sec.access.builtin.Access-Permissions.permissions_ca";
const char* const kGovernance = "dds.sec.access.builtin.Access-Permissions.governance";
const char* const kPermissions = "dds.sec.access.builtin.Access-Permissions.permissions";
const char* const kCryptoPlugin = "dds.sec.crypto.plugin";

template <class T, void (*Free)(T*)>
struct Deleter {
  void operator()(T* p) const { Free(p); }
};
using Bio = std::unique_ptr<BIO, Deleter<BIO, BIO_free_all>>;
using X509Ptr = std::unique_ptr<X509, Deleter<X509, X509_free>>;
using KeyPtr = std::unique_ptr<EVP_PKEY, Deleter<EVP_PKEY, EVP_PKEY_free>>;
using Pkcs7Ptr = std::unique_ptr<PKCS7, Deleter<PKCS7, PKCS7_free>>;
using CrlPtr = std::unique_ptr<X509_CRL, Deleter<X509_CRL, X509_CRL_free>>;
using StorePtr = std::unique_ptr<X509_STORE, Deleter<X509_STORE, X509_STORE_free>>;

// OpenSSL's reason for the last failure, or `fallback`.
std::string OpenSslReason(const std::string& fallback) {
  const unsigned long code = ERR_get_error();
  ERR_clear_error();
  if (code == 0) return fallback;
  char text[256];
  ERR_error_string_n(code, text, sizeof(text));
  return text;
}

[[noreturn]] void Fail(const std::filesystem::path& path, const std::string& what,
                       const std::string& role) {
  throw DdsError("DDS Security: " + path.string() + " (" + role + "): " + what +
                 "; refusing to start without a valid identity");
}

std::string ReadWhole(const std::filesystem::path& path, const std::string& role) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) Fail(path, "no such file", role);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) Fail(path, "cannot read it", role);
  if (text.str().empty()) Fail(path, "the file is empty", role);
  return text.str();
}

Bio MemoryBio(const std::string& text) {
  return Bio(BIO_new_mem_buf(text.data(), static_cast<int>(text.size())));
}

X509Ptr ReadCertificate(const std::filesystem::path& path, const std::string& role) {
  const std::string text = ReadWhole(path, role);
  Bio bio = MemoryBio(text);
  X509Ptr certificate(PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr));
  if (!certificate) Fail(path, "not a PEM certificate: " + OpenSslReason("unreadable"), role);
  return certificate;
}

std::string Subject(const X509* certificate) {
  Bio bio(BIO_new(BIO_s_mem()));
  X509_NAME_print_ex(bio.get(), X509_get_subject_name(certificate), 0, XN_FLAG_RFC2253);
  char* data = nullptr;
  const long size = BIO_get_mem_data(bio.get(), &data);
  return std::string(data, static_cast<std::size_t>(size));
}

// Verifies the S/MIME signature of `path` against the permissions CA alone.
void CheckSigned(const std::filesystem::path& path, X509* permissions_ca, const std::string& role) {
  const std::string text = ReadWhole(path, role);
  Bio bio = MemoryBio(text);
  BIO* content_raw = nullptr;
  Pkcs7Ptr pkcs7(SMIME_read_PKCS7(bio.get(), &content_raw));
  Bio content(content_raw);
  if (!pkcs7) Fail(path, "not an S/MIME signed document: " + OpenSslReason("unreadable"), role);
  StorePtr store(X509_STORE_new());
  X509_STORE_add_cert(store.get(), permissions_ca);
  Bio out(BIO_new(BIO_s_mem()));
  if (PKCS7_verify(pkcs7.get(), nullptr, store.get(), content.get(), out.get(), PKCS7_TEXT) != 1) {
    Fail(path,
         "its signature does not verify against the permissions CA: " +
             OpenSslReason("bad signature"),
         role);
  }
}

std::string FileUri(const std::filesystem::path& path) {
  return "file://" + std::filesystem::absolute(path).string();
}

}  // namespace

SecurityFiles SecurityFilesIn(const std::filesystem::path& dir) {
  SecurityFiles files{dir / "identity_ca.pem",    dir / "cert.pem",       dir / "key.pem",
                      dir / "permissions_ca.pem", dir / "governance.p7s", dir / "permissions.p7s",
                      {}};
  std::error_code error;
  if (std::filesystem::exists(dir / "identity_crl.pem", error)) {
    files.identity_crl = dir / "identity_crl.pem";
  }
  return files;
}

CheckedIdentity CheckSecurityFiles(const SecurityFiles& files) {
  X509Ptr identity_ca = ReadCertificate(files.identity_ca, "identity CA");
  X509Ptr certificate = ReadCertificate(files.certificate, "identity certificate");
  KeyPtr ca_key(X509_get_pubkey(identity_ca.get()));
  if (!ca_key || X509_verify(certificate.get(), ca_key.get()) != 1) {
    ERR_clear_error();
    Fail(files.certificate, "not signed by the identity CA " + files.identity_ca.string(),
         "identity certificate");
  }
  if (X509_cmp_current_time(X509_get0_notBefore(certificate.get())) > 0) {
    Fail(files.certificate, "not valid yet (check the clock)", "identity certificate");
  }
  if (X509_cmp_current_time(X509_get0_notAfter(certificate.get())) < 0) {
    Fail(files.certificate, "expired", "identity certificate");
  }
  if (!files.identity_crl.empty()) {
    const std::string text = ReadWhole(files.identity_crl, "revocation list");
    Bio bio = MemoryBio(text);
    CrlPtr crl(PEM_read_bio_X509_CRL(bio.get(), nullptr, nullptr, nullptr));
    if (!crl) {
      Fail(files.identity_crl, "not a PEM revocation list: " + OpenSslReason("unreadable"),
           "revocation list");
    }
    if (!ca_key || X509_CRL_verify(crl.get(), ca_key.get()) != 1) {
      ERR_clear_error();
      Fail(files.identity_crl, "not signed by the identity CA " + files.identity_ca.string(),
           "revocation list");
    }
    X509_REVOKED* revoked = nullptr;
    if (X509_CRL_get0_by_cert(crl.get(), &revoked, certificate.get()) == 1) {
      Fail(files.certificate, "revoked (on " + files.identity_crl.string() + ")",
           "identity certificate");
    }
  }
  {
    const std::string text = ReadWhole(files.private_key, "private key");
    Bio bio = MemoryBio(text);
    KeyPtr key(PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr));
    if (!key) {
      Fail(files.private_key, "not an unencrypted PEM private key: " + OpenSslReason("unreadable"),
           "private key");
    }
    if (X509_check_private_key(certificate.get(), key.get()) != 1) {
      ERR_clear_error();
      Fail(files.private_key, "does not belong to " + files.certificate.string(), "private key");
    }
  }
  X509Ptr permissions_ca = ReadCertificate(files.permissions_ca, "permissions CA");
  CheckSigned(files.governance, permissions_ca.get(), "governance");
  CheckSigned(files.permissions, permissions_ca.get(), "permissions");
  char common_name[256] = {};
  X509_NAME_get_text_by_NID(X509_get_subject_name(certificate.get()), NID_commonName, common_name,
                            sizeof(common_name));
  return {Subject(certificate.get()), common_name};
}

std::vector<std::pair<std::string, std::string>> SecurityProperties(const SecurityFiles& files) {
  std::vector<std::pair<std::string, std::string>> properties{
          {kAuthPlugin, "builtin.PKI-DH"},
          {kIdentityCa, FileUri(files.identity_ca)},
          {kCertificate, FileUri(files.certificate)},
          {kPrivateKey, FileUri(files.private_key)},
          {kAccessPlugin, "builtin.Access-Permissions"},
          {kPermissionsCa, FileUri(files.permissions_ca)},
          {kGovernance, FileUri(files.governance)},
          {kPermissions, FileUri(files.permissions)},
          {kCryptoPlugin, "builtin.AES-GCM-GMAC"}};
  if (!files.identity_crl.empty()) properties.emplace_back(kIdentityCrl, FileUri(files.identity_crl));
  return properties;
}

std::optional<SecurityFiles> SecurityFilesFromProperties(
    const std::vector<std::pair<std::string, std::string>>& properties) {
  auto find = [&](const char* name) -> std::optional<std::string> {
    for (const auto& [key, value] : properties) {
      if (key == name) return value;
    }
    return std::nullopt;
  };
  if (!find(kAuthPlugin)) return std::nullopt;
  auto file = [&](const char* name, bool optional = false) -> std::filesystem::path {
    const std::optional<std::string> value = find(name);
    if (!value && optional) return {};
    if (!value) throw DdsError(std::string("DDS Security: property ") + name + " is not set");
    if (value->rfind("file:", 0) != 0) {
      throw DdsError(std::string("DDS Security: property ") + name + " = '" + *value +
                     "': only file: URIs are supported");
    }
    std::string path = value->substr(5);
    if (path.rfind("//", 0) == 0) path = path.substr(2);  // file:///abs -> /abs
    return path;
  };
  return SecurityFiles{file(kIdentityCa),    file(kCertificate), file(kPrivateKey),
                       file(kPermissionsCa), file(kGovernance),  file(kPermissions),
                       file(kIdentityCrl, true)};
}

}  // namespace pena::services
