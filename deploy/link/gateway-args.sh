# Sourced by team-link-run.sh: the pena-gateway command lines of the two ends for one run
# (pena-gateway's DDS side: --dds-domain, --role; docs/gateway.md). Uses $out, $bld_domain,
# $post_domain, $bld_profile, $post_profile, ${bld_files[@]}, ${post_files[@]}, $gateway_bin,
# $link_insecure, $gw_security_profile and the addresses of netns-lib.sh. The link is sealed with
# a key made for the run ($out/gateway/link.key, docs/security.md) unless link_insecure=1. With
# gw_security_profile (a gateway identity's dds-profile.xml) both ends join their domains with
# DDS Security, as participant profile pena_loopback_secure.
# gateway_pair_args RATE_KBIT DELAY_S LOSS: sets gw_bld_args and gw_post_args.
gateway_pair_args() {
  local rate_kbit=$1 delay_s=$2 loss=$3 budget
  # 90 % of the link rate, counting IPv4 + UDP + Ethernet headers (42 bytes) as tbf does
  # (docs/gateway.md, "Scheduler policy"). Runs until SIGTERM (--duration-s 0).
  budget=$(awk "BEGIN{print $rate_kbit*1000*0.9}")
  local common=(--budget-bit-s "$budget" --overhead-bytes 42 --duration-s 0
                --emulate-delay-s "$delay_s" --emulate-loss "$loss")
  if [[ ${link_insecure:-0} == 1 ]]; then
    common+=(--insecure-link)
  else
    rm -f "$out/gateway/link.key"
    "$gateway_bin" --generate-link-key "$out/gateway/link.key" > /dev/null
    common+=(--link-key "$out/gateway/link.key")
  fi
  local file bld_dds=() post_dds=()
  for file in "${bld_files[@]}"; do [[ $file == --profiles-file ]] || bld_dds+=(--dds-profiles-file "$file"); done
  for file in "${post_files[@]}"; do [[ $file == --profiles-file ]] || post_dds+=(--dds-profiles-file "$file"); done
  local bld_gw_profile=$bld_profile post_gw_profile=$post_profile
  if [[ -n ${gw_security_profile:-} ]]; then
    bld_dds+=(--dds-profiles-file "$gw_security_profile"); post_dds+=(--dds-profiles-file "$gw_security_profile")
    bld_gw_profile=pena_loopback_secure; post_gw_profile=pena_loopback_secure
  fi
  gw_bld_args=("${common[@]}" --bind "$LINK_BUILDING_IP:7700" --peer "$LINK_POST_IP:7700"
               --name building --stats "$out/gateway/building.json"
               --dds-domain "$bld_domain" --role building --dds-participant-profile "$bld_gw_profile"
               "${bld_dds[@]}")
  gw_post_args=("${common[@]}" --bind "$LINK_POST_IP:7700" --peer "$LINK_BUILDING_IP:7700"
                --name post --stats "$out/gateway/post.json"
                --dds-domain "$post_domain" --role command-post --dds-participant-profile "$post_gw_profile"
                "${post_dds[@]}")
}
