#!/usr/bin/env bash
# Calibration of the linmotor-flex plant on ONE experiment: thesis Table 2-2 case C (10:1 ellipse
# at 7 rad/s, LTCF-SARC and GTCF-SARC at the thesis gains; thesis RMS 5.66 / 2.20 um, ratio 0.39).
# Grid over the parameters appendix A leaves open: the mode frequencies (middle and top of A's
# ranges X 100-200 Hz, Y 40-80 Hz), each axis's mode damping ratio and the Stribeck extra friction
# (A.3). Prints one CSV row per point (64 points, 2.2 min on 2 cores) and, on stderr, the chosen
# point (the catalog's values). Cost  |ln(GTCF / 2.20)| + |ln((GTCF / LTCF) / 0.389)|; no point
# reaches the thesis's ratio, so many points cost within a few hundredths of each other. Chosen:
# among the points within 0.05 of the lowest cost, the one furthest from the mode's instability
# edge (largest min(zeta_x, zeta_y)), then the lowest cost. (The plain lowest cost, zeta_x 0.35,
# sits on the edge: it went unstable on thesis-circle and thesis-darc-sets.)
# A first pass at 150/60 Hz with zeta 0.35-0.8 on both axes showed zeta_y <= 0.35 unstable at the
# thesis gains and zeta >= 0.45 the rigid model's numbers; this grid brackets that edge.
#
#   bench/linmotor_flex_calibration.sh [NETMC] > calibration.csv
#   ZETAS_X="0.3 0.5" ZETAS_Y="0.3 0.5" STRIBECK="0 0.05" FREQS="150:60 100:40" bench/...
set -euo pipefail
netmc=${1:-build-stage/client/netmc}
zetas_x=${ZETAS_X:-"0.35 0.45"}
zetas_y=${ZETAS_Y:-"0.38 0.41 0.45 0.6"}
stribeck=${STRIBECK:-"0 0.1 0.2 0.3"}
freqs=${FREQS:-"150:60 200:80"}
echo "fx_hz,fy_hz,zeta_x,zeta_y,stribeck_extra_v,ltcf_rms_um,gtcf_rms_um,ratio,cost"
rows=""
for f in $freqs; do
  fx=${f%%:*}; fy=${f##*:}
  for zx in $zetas_x; do
    for zy in $zetas_y; do
      for sv in $stribeck; do
        plant="linmotor-flex:x.mode_frequency_hz=$fx,y.mode_frequency_hz=$fy,x.mode_damping=$zx,y.mode_damping=$zy,stribeck_extra_v=$sv"
        out=$("$netmc" sim --preset thesis-ellipse --controller ltcf-sarc,gtcf-sarc --plant "$plant" --threads 2)
        ltcf=$(awk '$1 == "ltcf-sarc" { print $2 }' <<<"$out")
        gtcf=$(awk '$1 == "gtcf-sarc" { print $2 }' <<<"$out")
        row=$(awk -v fx="$fx" -v fy="$fy" -v zx="$zx" -v zy="$zy" -v sv="$sv" -v l="$ltcf" -v g="$gtcf" 'BEGIN {
          r = g / l; c = log(g / 2.20); if (c < 0) c = -c; d = log(r / 0.3887); if (d < 0) d = -d;
          printf "%s,%s,%s,%s,%s,%.2f,%.2f,%.3f,%.3f\n", fx, fy, zx, zy, sv, l, g, r, c + d }')
        echo "$row"
        rows+="$row"$'\n'
      done
    done
  done
done
chosen=$(awk -F, 'NF == 9 { row[NR] = $0; cost[NR] = $9; z[NR] = ($3 < $4 ? $3 : $4);
                               if (best == "" || $9 < best) best = $9 }
  END { for (i in row) if (cost[i] <= best + 0.05 && (pick == "" || z[i] > z[pick] ||
                                                      (z[i] == z[pick] && cost[i] < cost[pick]))) pick = i;
        print row[pick] }' <<<"${rows%$'\n'}")
echo "lowest cost: $(sort -t, -k9 -g <<<"${rows%$'\n'}" | head -1)" >&2
echo "chosen: $chosen" >&2
