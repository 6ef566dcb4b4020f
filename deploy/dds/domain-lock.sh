# Sourced by the scripts that start PeNa processes on a DDS domain of their own.
# pena_lock_dds_domain VAR: the first domain in 30..99 that no other run on this machine holds
# (/tmp/pena-dds-domain-N.lock, the same locks as the C++ tests'), into VAR; the lock stays held
# until this shell exits, so parallel runs (two checkouts, ctest -j) never share a domain.
pena_lock_dds_domain() {
  local domain fd
  for domain in $(seq 30 99); do
    exec {fd}>"/tmp/pena-dds-domain-$domain.lock"
    if flock -n "$fd"; then
      printf -v "$1" '%s' "$domain"
      return 0
    fi
    exec {fd}>&-
  done
  echo "no free DDS domain in 30..99" >&2
  return 1
}
