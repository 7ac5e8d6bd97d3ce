#!/usr/bin/env bash
# The cloud collapse's work-precision runs (issue #17, docs/time_integration.md "Work-precision of
# the collapse"): default resolution to 0.975 t_ff (before the sink forms), each stepper at a few
# settings on one thread, two runs at a time (about 17 minutes on two cores), then the chart.
# Usage: scripts/collapse_work_precision.sh OUT_DIR
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: $0 OUT_DIR}
mkdir -p "$out"
bin=build/bin/cloud_collapse
common=(--variant cleaning --particles 2000 --overclean 4 --t-end 0.975 --threads 1 --no-render --output-every 0)  # session 23-26 defaults
top=0.005  # the diagnostics interval, in t_ff (every time option of the collapse is in t_ff)
# the reference: ARK436L2SA at rtol 1e-8 without the CFL cap (rtol 1e-6 and 1e-3 lie within
# 1e-4 of it: that is the floor the density solve's tolerance sets, not a time error)
runs=(
  "ref|--stepper ARKODE_ARK436L2SA_ERK_6_3_4 --rtol 1e-8 --step-cap off"
  "lf_0.3|" "lf_0.15|--courant 0.15" "lf_0.1|--courant 0.1" "lf_0.05|--courant 0.05"
  "blk_0.3|--stepper leapfrog-blocks --max-dt $top" "blk_0.15|--stepper leapfrog-blocks --max-dt $top --courant 0.15"
  "blk_0.1|--stepper leapfrog-blocks --max-dt $top --courant 0.1"
  "mri_0.3|--stepper mri-ARKODE_MRI_GARK_ERK33a --max-dt $top"
  "ark436_1e-3|--stepper ARKODE_ARK436L2SA_ERK_6_3_4 --rtol 1e-3 --step-cap off"
  "ark436_1e-6|--stepper ARKODE_ARK436L2SA_ERK_6_3_4 --rtol 1e-6 --step-cap off"
  "dp5_1e-4|--stepper ARKODE_DORMAND_PRINCE_7_4_5 --rtol 1e-4"
)
for r in "${runs[@]}"; do  # a run whose summary exists is not made again
  name=${r%%|*} opts=${r#*|}
  [ -f "$out/$name/summary_cleaning.csv" ] && continue
  # shellcheck disable=SC2086
  echo "$bin ${common[*]} $opts --out $out/$name > $out/$name.log 2>&1"
done | xargs -P 2 -I{} sh -c '{}' || true  # a run that fails is left out of the chart below
labels=()
for r in "${runs[@]:1}"; do
  name=${r%%|*}
  [ -f "$out/$name/summary_cleaning.csv" ] || continue
  case $name in lf_*) l="leapfrog C=${name#lf_}";; blk_*) l="blocks C=${name#blk_}";;
    mri_*) l="MRI-ERK33a C=${name#mri_}";; ark436_*) l="ARK436 rtol=${name#ark436_}";; dp5_*) l="DP5 rtol=${name#dp5_}";; esac
  labels+=("$out/$name=$l")
done
/usr/bin/python3 vis/collapse_work_precision.py "$out/work_precision.png" "$out/ref" "${labels[@]}" \
  --reference-label "ARK436L2SA rtol 1e-8"
