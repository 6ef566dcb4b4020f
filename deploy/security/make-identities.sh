#!/usr/bin/env bash
# DDS Security material for one mission (docs/security.md, "DDS Security"): an identity CA, a
# permissions CA, the signed governance, and one identity per role with its signed permissions.
#
#   deploy/security/make-identities.sh [options] OUT_DIR [ENTITY_ID...]
#
#   --operators LIST  operator identities, comma-separated (default: operator)
#   --days N          validity of new certificates and of the permissions (default 30)
#   --domains MIN-MAX DDS domain ids the governance and the permissions cover (default 0-232)
#   --revoke ID       revoke identity ID (a lost or captured device): its certificate goes on
#                     the identity CA's revocation list, its directory moves to ca/revoked/
#                     (repeatable)
#
# Roles: entity ENTITY_ID for each id given (pena-entity and its sensor driver), fusion, each
# operator (pena-console), gateway, monitor. OUT_DIR gets:
#   ca/                 the two CAs' keys: keep them off the devices (the mission's laptop);
#                       identity_crl.pem, the revocation list every identity carries a copy of
#   governance.xml      the domain rules, signed as <ID>/governance.p7s
#   <ID>/               what the device of identity ID carries, and all it carries:
#       identity_ca.pem identity_crl.pem permissions_ca.pem governance.p7s cert.pem key.pem
#       permissions.xml permissions.p7s, and dds-profile.xml (the participant profile
#       pena_loopback_secure, for tools that take only XML profiles)
# Idempotent: CAs, keys and certificates that exist are kept (a device keeps its identity); the
# governance and the permissions of every identity named are signed again, so running it again
# after adding an id, or with another --days, re-issues them. Needs openssl.
set -euo pipefail

usage() { sed -n '2,25p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }

OPERATORS=operator
DAYS=30
DOMAINS=0-232
REVOKE=()
while (($#)); do
  case $1 in
    --operators) OPERATORS=${2:?--operators needs a list}; shift 2 ;;
    --days) DAYS=${2:?--days needs a number}; shift 2 ;;
    --domains) DOMAINS=${2:?--domains needs MIN-MAX}; shift 2 ;;
    --revoke) REVOKE+=("${2:?--revoke needs an id}"); shift 2 ;;
    -h|--help) usage ;;
    --*) echo "make-identities.sh: unknown option $1" >&2; usage ;;
    *) break ;;
  esac
done
OUT=${1:-}
[[ -n $OUT ]] || usage
shift
ENTITIES=("$@")
IFS=, read -r -a OPERATOR_IDS <<< "$OPERATORS"
[[ $DAYS =~ ^[1-9][0-9]*$ ]] || { echo "make-identities.sh: --days must be a positive integer, got '$DAYS'" >&2; exit 2; }
[[ $DOMAINS =~ ^([0-9]+)-([0-9]+)$ ]] ||
  { echo "make-identities.sh: --domains must be MIN-MAX, got '$DOMAINS'" >&2; exit 2; }
DOMAIN_MIN=${BASH_REMATCH[1]}
DOMAIN_MAX=${BASH_REMATCH[2]}
for id in "${ENTITIES[@]}" "${OPERATOR_IDS[@]}"; do
  # Ids become certificate subjects, partition names and directory names.
  [[ $id =~ ^[A-Za-z0-9_-]{1,32}$ ]] ||
    { echo "make-identities.sh: id '$id' must be 1-32 of A-Z a-z 0-9 _ -" >&2; exit 2; }
  case $id in ca|fusion|gateway|monitor)
    echo "make-identities.sh: '$id' is a role name, not an entity or operator id" >&2; exit 2 ;;
  esac
done
command -v openssl > /dev/null || { echo "make-identities.sh: openssl not found" >&2; exit 1; }

umask 077
mkdir -p "$OUT/ca"
OUT=$(cd "$OUT" && pwd)
CA=$OUT/ca
ORG="PeNa"

# A self-signed CA certificate and key (ECDSA P-256), kept if present.
# The permissions CA signs documents itself (S/MIME), so it needs digitalSignature as well.
make_ca() {
  local name=$1 cn=$2 usage=$3
  [[ -s $CA/$name.pem && -s $CA/$name.key ]] && return
  openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -sha256 \
    -days $((DAYS * 12)) -subj "/O=$ORG/CN=$cn" \
    -addext basicConstraints=critical,CA:TRUE -addext keyUsage=critical,$usage \
    -keyout "$CA/$name.key" -out "$CA/$name.pem" 2> /dev/null
  echo "created $cn: $CA/$name.pem"
}
make_ca identity_ca "PeNa identity CA" keyCertSign,cRLSign
make_ca permissions_ca "PeNa permissions CA" keyCertSign,cRLSign,digitalSignature

# The revocation list of the identity CA (openssl ca keeps its database in ca/). Always
# written, empty or not: every participant loads it, and refuses a peer whose certificate is on
# it.
cat > "$CA/openssl.cnf" <<CNF
[ ca ]
default_ca = pena
[ pena ]
database = $CA/index.txt
crlnumber = $CA/crlnumber
certificate = $CA/identity_ca.pem
private_key = $CA/identity_ca.key
default_md = sha256
default_crl_days = $DAYS
CNF
[[ -f $CA/index.txt ]] || : > "$CA/index.txt"
[[ -f $CA/crlnumber ]] || echo 01 > "$CA/crlnumber"
mkdir -p "$CA/revoked"
for id in "${REVOKE[@]}"; do
  [[ -s $OUT/$id/cert.pem ]] ||
    { echo "make-identities.sh: --revoke $id: no identity $OUT/$id/cert.pem" >&2; exit 1; }
  openssl ca -config "$CA/openssl.cnf" -revoke "$OUT/$id/cert.pem" -crl_reason keyCompromise \
    2> /dev/null || { echo "make-identities.sh: cannot revoke $id" >&2; exit 1; }
  rm -rf "$CA/revoked/$id"
  mv "$OUT/$id" "$CA/revoked/$id"
  echo "revoked identity $id (certificate on the revocation list; its files moved to $CA/revoked/$id)"
done
openssl ca -config "$CA/openssl.cnf" -gencrl -out "$CA/identity_crl.pem" 2> /dev/null

# S/MIME-signs $1 (XML) into $2 with the permissions CA, as DDS Security expects.
sign() {
  openssl smime -sign -in "$1" -text -out "$2" -signer "$CA/permissions_ca.pem" \
    -inkey "$CA/permissions_ca.key"
}

# The topics, grouped as the permissions use them (services/common/topics.hpp,
# services/sensors/sensor_topics.hpp).
ENTITY_TOPICS=(pena/entity/pose pena/entity/status pena/entity/line_map_delta
  pena/entity/line_map_snapshot pena/entity/reference_scan)
SENSOR_TOPICS=(pena/sensors/scan pena/sensors/gyro pena/sensors/compass pena/sensors/stride
  pena/sensors/wheel_odometry pena/sensors/status)
FUSION_TOPICS=(pena/fusion/correction pena/fusion/global_map_delta pena/fusion/global_map_snapshot)
OPERATOR_TOPICS=(pena/operator/correction pena/annotation)
SYNC_TOPICS=(pena/sync_request)
LINK_TOPICS=(pena/gateway/link_health)

# Governance: nobody unauthenticated joins; discovery and liveliness encrypted; every topic's
# submessages signed (metadata), and the data of topics that carry positions, map geometry,
# scans or corrections encrypted. Status heartbeats and sync requests carry neither: signed only.
topic_rule() {
  local expression=$1 data=$2
  cat <<XML
      <topic_rule>
        <topic_expression>$expression</topic_expression>
        <enable_discovery_protection>true</enable_discovery_protection>
        <enable_liveliness_protection>true</enable_liveliness_protection>
        <enable_read_access_control>true</enable_read_access_control>
        <enable_write_access_control>true</enable_write_access_control>
        <metadata_protection_kind>SIGN</metadata_protection_kind>
        <data_protection_kind>$data</data_protection_kind>
      </topic_rule>
XML
}
{
  cat <<XML
<?xml version="1.0" encoding="UTF-8"?>
<!-- PeNa governance (deploy/security/make-identities.sh; docs/security.md). -->
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-Security/20170801/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      <domains><id_range><min>$DOMAIN_MIN</min><max>$DOMAIN_MAX</max></id_range></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
XML
  topic_rule "pena/entity/status" NONE
  topic_rule "pena/sensors/status" NONE
  topic_rule "pena/sync_request" NONE
  topic_rule "*" ENCRYPT
  cat <<XML
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
XML
} > "$OUT/governance.xml.new"
mv "$OUT/governance.xml.new" "$OUT/governance.xml"
sign "$OUT/governance.xml" "$OUT/governance.p7s"

# <topics> of the names given.
topics_xml() {
  local topic
  echo "          <topics>"
  for topic in "$@"; do echo "            <topic>$topic</topic>"; done
  echo "          </topics>"
}

NOT_BEFORE=$(date -u +%Y-%m-%dT%H:%M:%S)
NOT_AFTER=$(date -u -d "+$DAYS days" +%Y-%m-%dT%H:%M:%S)

# One identity: key, certificate signed by the identity CA, permissions, profile.
# $1 name, $2 OU (role), $3 its allow rules (allow_rule_xml).
make_identity() {
  local name=$1 role=$2 rules=$3
  local dir=$OUT/$name
  mkdir -p "$dir"
  local subject="/O=$ORG/OU=$role/CN=$name"
  if [[ ! -s $dir/key.pem || ! -s $dir/cert.pem ]]; then
    openssl req -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -sha256 \
      -subj "$subject" -keyout "$dir/key.pem" -out "$dir/cert.csr" 2> /dev/null
    openssl x509 -req -in "$dir/cert.csr" -CA "$CA/identity_ca.pem" -CAkey "$CA/identity_ca.key" \
      -CAcreateserial -days "$DAYS" -sha256 -out "$dir/cert.pem" 2> /dev/null
    rm -f "$dir/cert.csr"
    echo "issued identity $name ($role): $dir/cert.pem"
  fi
  # The grant names the certificate's subject as Fast DDS prints it (RFC 2253, most specific
  # first).
  local rfc2253
  rfc2253=$(openssl x509 -in "$dir/cert.pem" -noout -subject -nameopt RFC2253 | sed 's/^subject=//')
  cat > "$dir/permissions.xml" <<XML
<?xml version="1.0" encoding="UTF-8"?>
<!-- Permissions of $name ($role), deploy/security/make-identities.sh; docs/security.md. -->
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-Security/20170801/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="$name">
      <subject_name>$rfc2253</subject_name>
      <validity><not_before>$NOT_BEFORE</not_before><not_after>$NOT_AFTER</not_after></validity>
$rules
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
XML
  sign "$dir/permissions.xml" "$dir/permissions.p7s"
  cp "$CA/identity_ca.pem" "$dir/identity_ca.pem"
  cp "$CA/identity_crl.pem" "$dir/identity_crl.pem"
  cp "$CA/permissions_ca.pem" "$dir/permissions_ca.pem"
  cp "$OUT/governance.p7s" "$dir/governance.p7s"
  write_profile "$dir"
}

# <dds-profile.xml>: pena_loopback with this identity, for tools that take only XML profiles
# (load after deploy/dds/pena-loopback.xml, which defines the transports).
write_profile() {
  local dir=$1 f
  {
    cat <<XML
<?xml version="1.0" encoding="UTF-8" ?>
<!-- This identity's secured loopback participant (make-identities.sh). Load after
     deploy/dds/pena-loopback.xml; use with participant profile pena_loopback_secure. -->
<profiles xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <participant profile_name="pena_loopback_secure">
    <rtps>
      <userTransports>
        <transport_id>pena_loopback_udp</transport_id>
        <transport_id>pena_shm</transport_id>
      </userTransports>
      <useBuiltinTransports>false</useBuiltinTransports>
      <builtin>
        <discovery_config>
          <leaseDuration><sec>10</sec></leaseDuration>
          <leaseAnnouncement><sec>1</sec></leaseAnnouncement>
          <initialAnnouncements><count>10</count><period><nanosec>100000000</nanosec></period></initialAnnouncements>
        </discovery_config>
        <initialPeersList><locator><udpv4><address>127.0.0.1</address></udpv4></locator></initialPeersList>
      </builtin>
      <propertiesPolicy>
        <properties>
XML
    for f in "dds.sec.auth.plugin=builtin.PKI-DH" \
      "dds.sec.auth.builtin.PKI-DH.identity_ca=file://$dir/identity_ca.pem" \
      "dds.sec.auth.builtin.PKI-DH.identity_certificate=file://$dir/cert.pem" \
      "dds.sec.auth.builtin.PKI-DH.identity_crl=file://$dir/identity_crl.pem" \
      "dds.sec.auth.builtin.PKI-DH.private_key=file://$dir/key.pem" \
      "dds.sec.access.plugin=builtin.Access-Permissions" \
      "dds.sec.access.builtin.Access-Permissions.permissions_ca=file://$dir/permissions_ca.pem" \
      "dds.sec.access.builtin.Access-Permissions.governance=file://$dir/governance.p7s" \
      "dds.sec.access.builtin.Access-Permissions.permissions=file://$dir/permissions.p7s" \
      "dds.sec.crypto.plugin=builtin.AES-GCM-GMAC"; do
      echo "          <property><name>${f%%=*}</name><value>${f#*=}</value></property>"
    done
    cat <<XML
        </properties>
      </propertiesPolicy>
    </rtps>
  </participant>
</profiles>
XML
  } > "$dir/dds-profile.xml"
}

# Rules. Entities write in the partition named after their id (docs/security.md), and read the
# sensor topics only there; every other reader subscribes to all partitions ("*"). Fusion,
# operators, gateway and monitor write in the default partition.
#
# Fast DDS decides a reader's or writer's partitions by the first allow_rule that names its
# topic, and accepts a partition if any <subscribe> (or <publish>) of that rule names it, not
# only the one that names the topic. So topics with different partitions go in separate
# allow_rules.
allow_rule_xml() {  # $1 publish XML, $2 subscribe XML
  cat <<XML
      <allow_rule>
        <domains><id_range><min>$DOMAIN_MIN</min><max>$DOMAIN_MAX</max></id_range></domains>
$1
$2
      </allow_rule>
XML
}
publish_xml() {  # $1 partition ("" = default), then topics
  local partition=$1
  shift
  echo "        <publish>"
  topics_xml "$@"
  if [[ -n $partition ]]; then
    echo "          <partitions><partition>$partition</partition></partitions>"
  fi
  echo "        </publish>"
}
# Readers: in every partition ("*" covers the default one too in permissions), or in those given.
subscribe_xml() {  # then topics
  subscribe_in_xml "*" "$@"
}
subscribe_in_xml() {  # $1 partitions, comma-separated, then topics
  local partitions=$1 partition
  shift
  echo "        <subscribe>"
  topics_xml "$@"
  echo "          <partitions>"
  IFS=, read -r -a partitions <<< "$partitions"
  for partition in "${partitions[@]}"; do echo "            <partition>$partition</partition>"; done
  echo "          </partitions>"
  echo "        </subscribe>"
}

# An entity reads its own sensors (its driver's, in its partition) and nothing of another
# entity's; the fusion's corrections and map and the sync requests it answers come from the
# default partition.
for id in "${ENTITIES[@]}"; do
  make_identity "$id" entity \
    "$(allow_rule_xml "$(publish_xml "$id" "${ENTITY_TOPICS[@]}" "${SENSOR_TOPICS[@]}" "${SYNC_TOPICS[@]}")" \
                      "$(subscribe_in_xml "$id" "${SENSOR_TOPICS[@]}")")
$(allow_rule_xml "" "$(subscribe_xml "${FUSION_TOPICS[@]}" "${SYNC_TOPICS[@]}")")"
done
# The fusion relays operator decisions as annotations (services/fusion, the operator log) and
# answers each operator correction on its topic (applied or refused, for the consoles).
make_identity fusion fusion "$(allow_rule_xml \
  "$(publish_xml "" "${FUSION_TOPICS[@]}" pena/annotation pena/operator/correction "${SYNC_TOPICS[@]}")" \
  "$(subscribe_xml "${ENTITY_TOPICS[@]}" "${FUSION_TOPICS[@]}" "${OPERATOR_TOPICS[@]}" "${SYNC_TOPICS[@]}")")"
# Operators (pena-console) also show the radio link's health that the gateways publish.
for id in "${OPERATOR_IDS[@]}"; do
  make_identity "$id" operator "$(allow_rule_xml \
    "$(publish_xml "" "${OPERATOR_TOPICS[@]}" "${SYNC_TOPICS[@]}")" \
    "$(subscribe_xml "${ENTITY_TOPICS[@]}" "${FUSION_TOPICS[@]}" "${OPERATOR_TOPICS[@]}" "${SYNC_TOPICS[@]}" \
                     "${LINK_TOPICS[@]}")")"
done
# The gateway bridges two domains: on each side it republishes what the other side's members
# published, so it writes and reads every PeNa topic, in every partition.
make_identity gateway gateway "$(allow_rule_xml "$(publish_xml "*" "pena/*")" "$(subscribe_xml "pena/*")")"
make_identity monitor monitor "$(allow_rule_xml "" \
  "$(subscribe_xml "${ENTITY_TOPICS[@]}" "${FUSION_TOPICS[@]}" "${OPERATOR_TOPICS[@]}" "${SYNC_TOPICS[@]}" \
                   "${LINK_TOPICS[@]}")")"
echo "security material in $OUT (identities: ${ENTITIES[*]} fusion ${OPERATOR_IDS[*]} gateway monitor)"
