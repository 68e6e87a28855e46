#!/bin/sh
# tests/sim/cigi_tshark_check.sh: Wireshark's CIGI dissector reads what our encoders and the IG write as meant: one
# host datagram of every packet (both byte orders) and the IG's Start of Frame, wrapped in UDP to port 8004, decoded by
# `tshark -d udp.port==8004,cigi` with no other preference, field by field. Skips without tshark and text2pcap.
. tests/lib.sh
B=${B:-build}
if ! command -v tshark >/dev/null || ! command -v text2pcap >/dev/null; then
  t_skip "tshark decodes CIGI 3.3" "no tshark/text2pcap (Debian: tshark)"; t_summary; exit
fi
[ -x "$B/cigi_seeds" ] || make -s "$B/cigi_seeds" >/dev/null || exit 1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$B/cigi_seeds" "$tmp" && (cd "$tmp" && "$OLDPWD/$B/cigi_seeds" --sof sof) || exit 1

# fields FILE SRCPORT FIELD...: the values tshark decodes, one line "field=value" each (values of repeated fields
# joined by commas).
fields() {
  f=$1 port=$2; shift 2
  od -Ax -tx1 -v "$tmp/$f" >"$tmp/$f.txt"
  text2pcap -q -u "$port,8004" "$tmp/$f.txt" "$tmp/$f.pcap" >/dev/null 2>&1 || return 1
  args=""; for x in "$@"; do args="$args -e $x"; done
  tshark -r "$tmp/$f.pcap" -d udp.port==8004,cigi -T fields -E header=y -E separator=/t $args 2>/dev/null |
    awk -F'\t' 'NR == 1 {for (i = 1; i <= NF; i++) h[i] = $i; next} {for (i = 1; i <= NF; i++) print h[i] "=" $i}'
}

# The values cigi_seeds.c's every_packet writes, as tshark prints them.
HOST="cigi.version=3 cigi.ig_control.db_number=7 cigi.ig_control.ig_mode=1 cigi.ig_control.timestamp_valid=1
cigi.ig_control.minor_version=3 cigi.ig_control.host_frame_number=1 cigi.ig_control.timestamp=5678
cigi.ig_control.last_ig_frame_number=99 cigi.entity_control.entity_id=0 cigi.entity_control.entity_state=1
cigi.entity_control.parent_id=5 cigi.entity_control.roll=1.5 cigi.entity_control.pitch=-2.5
cigi.entity_control.yaw=270.25 cigi.entity_control.lat_xoff=47.123456789 cigi.entity_control.lon_yoff=-122.5
cigi.entity_control.alt_zoff=1500.25 cigi.view_control.view_id=0 cigi.view_control.group_id=0
cigi.view_control.xoff_enable=1 cigi.view_control.yoff_enable=0 cigi.view_control.zoff_enable=1
cigi.view_control.roll_enable=0 cigi.view_control.pitch_enable=0 cigi.view_control.yaw_enable=1
cigi.view_control.xoff=1.25 cigi.view_control.yoff=-0.5 cigi.view_control.zoff=-2 cigi.view_control.roll=4
cigi.view_control.pitch=5 cigi.view_control.yaw=6 cigi.view_def.view_id=0 cigi.view_def.group_id=2
cigi.view_def.near_enable=1 cigi.view_def.far_enable=1 cigi.view_def.left_enable=1 cigi.view_def.right_enable=1
cigi.view_def.top_enable=1 cigi.view_def.bottom_enable=1 cigi.view_def.mirror_mode=1
cigi.view_def.pixel_replication=2 cigi.view_def.projection_type=0 cigi.view_def.reorder=1 cigi.view_def.view_type=5
cigi.view_def.near=0.5 cigi.view_def.far=20000 cigi.view_def.left=-40 cigi.view_def.right=41 cigi.view_def.top=30
cigi.view_def.bottom=-31 cigi.celestial_sphere_control.hour=14 cigi.celestial_sphere_control.minute=35
cigi.celestial_sphere_control.sun_enable=1 cigi.celestial_sphere_control.star_enable=1
cigi.celestial_sphere_control.date_time_valid=1 cigi.celestial_sphere_control.date=6212024
cigi.celestial_sphere_control.star_intensity=50 cigi.atmosphere_control.atmospheric_model_enable=1
cigi.atmosphere_control.humidity=40 cigi.atmosphere_control.air_temp=15
cigi.atmosphere_control.visibility_range=30000 cigi.atmosphere_control.horiz_wind=7.5
cigi.atmosphere_control.vert_wind=0.5 cigi.atmosphere_control.wind_direction=225
cigi.atmosphere_control.barometric_pressure=1013.25 cigi.weather_control.entity_region_id=0
cigi.weather_control.layer_id=2 cigi.weather_control.humidity=80 cigi.weather_control.weather_enable=1
cigi.weather_control.scud_enable=1 cigi.weather_control.random_winds_enable=0
cigi.weather_control.random_lightning_enable=1 cigi.weather_control.cloud_type=7 cigi.weather_control.scope=0
cigi.weather_control.severity=3 cigi.weather_control.air_temp=5 cigi.weather_control.visibility_range=8000
cigi.weather_control.scud_frequency=25 cigi.weather_control.coverage=62.5 cigi.weather_control.base_elevation=1200
cigi.weather_control.thickness=800 cigi.weather_control.transition_band=100 cigi.weather_control.horiz_wind=12
cigi.weather_control.vert_wind=1 cigi.weather_control.wind_direction=290
cigi.weather_control.barometric_pressure=900 cigi.weather_control.aerosol_concentration=0.25"
SOF="cigi.version=3 cigi.sof.db_number=7 cigi.sof.ig_status=0 cigi.sof.ig_mode=1 cigi.sof.timestamp_valid=1
cigi.sof.earth_reference_model=0 cigi.sof.minor_version=3 cigi.byte_swap=0x8000 cigi.sof.ig_frame_number=4242
cigi.sof.timestamp=777 cigi.sof.last_host_frame_number=1234"

# check NAME FILE SRCPORT EXPECTED: every expected "field=value" is what tshark decoded.
check() {
  name=$1 f=$2 port=$3 want=$4
  got=$(fields "$f" "$port" $(for kv in $want; do echo "${kv%%=*}"; done))
  bad=""
  for kv in $want; do
    echo "$got" | grep -qxF "$kv" || bad="$bad $kv (got $(echo "$got" | grep "^${kv%%=*}=" | head -1))"
  done
  [ -z "$bad" ] && t_ok "$name" || t_fail "$name" "$bad"
}
check "tshark decodes a big-endian host datagram of every packet" every_packet_be 8004 "$HOST cigi.byte_swap=0x8000"
check "tshark decodes a little-endian host datagram of every packet" every_packet_le 8004 "$HOST cigi.byte_swap=0x0080"
check "tshark decodes the IG's Start of Frame" sof 8005 "$SOF"
t_summary
