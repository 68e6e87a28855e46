#!/bin/sh
# Generates the slab C tables with build/cumulo-slab, fits them with build/cumulo-slab-fit, writes data/slab_* + manifest.
# Usage (from the repo root): sh tools/slab/gen_tables.sh   (environment overrides below; PHOTONS=1e5 takes ~15 min on 2 cores)
set -eu
PHOTONS=${PHOTONS:-1e5}
THICK=${THICK:-"25 50 100 200 400 800 1600"}
THETAL=${THETAL:-"0 30 50 70"}
PHASE=${PHASE:-hg:0.85}
DEPTHS=${DEPTHS:-11}
THREADS=${THREADS:-2}
SEED=${SEED:-1000}
WORK=${WORK:-build/slab_tables}
DATA=${DATA:-data}
TAG=${TAG:-slab}
mkdir -p "$WORK" "$DATA"
start=$(date +%s)
log="$WORK/gen.log"
: >"$log"
i=0
# STAGES: any of sim, fit, manifest (FIT_ONLY=1 is the old spelling of STAGES="fit manifest")
STAGES=${STAGES:-"sim fit manifest"}
[ "${FIT_ONLY:-0}" = 1 ] && STAGES="fit manifest"
case " $STAGES " in *" sim "*) ;; *) THICK="" ;; esac
for t in $THICK; do
  for L in $THETAL; do
    mu=$(awk -v a="$L" 'BEGIN { printf "%.12f", cos(a * 3.14159265358979324 / 180) }')
    f=$(printf '%s/C_t%05d_L%02d.txt' "$WORK" "$t" "$L")
    s=$((SEED + i)); i=$((i + 1))
    t0=$(date +%s)
    build/cumulo-slab --thickness "$t" --mu0 "$mu" --phase "$PHASE" --photons "$PHOTONS" --threads "$THREADS" \
      --seed "$s" --depths "$DEPTHS" --report table --out "$f" --quiet
    echo "t=$t thetaL=$L seed=$s $(( $(date +%s) - t0 ))s" | tee -a "$log"
  done
done
sim=$(( $(date +%s) - start ))
if [ -z "$THICK" ]; then sim="(not re-run; see the per-run log)"; else cp "$log" "$WORK/gen_sim.log"; fi
t0=$(date +%s)
# eq. 3.32 and the log-separable form; the two fits are independent, so they run side by side (2 cores).
# (logsep2 -- P* also depending on depth -- has ~300 parameters per slice and takes ~30 s per slice: --model logsep2)
MODELS=${MODELS:-"bouthors logsep"}
case " $STAGES " in *" fit "*)
  for m in $MODELS; do
    build/cumulo-slab-fit --model "$m" --out "$DATA/${TAG}_fit" "$WORK"/C_t*_L*.txt >"$DATA/${TAG}_fit_report_$m.txt" &
    build/cumulo-slab-fit --model "$m" --holdout "$WORK"/C_t*_L*.txt >"$DATA/${TAG}_fit_holdout_$m.txt"
    wait
  done ;;
esac
fit=$(( $(date +%s) - t0 ))
# raw tables, compressed, so the fit can be redone without re-simulating
tar -C "$WORK" -czf "$DATA/${TAG}_C_tables.tar.gz" $(cd "$WORK" && ls C_t*_L*.txt)
{
  echo "# slab tables manifest (tools/slab/gen_tables.sh)"
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)  git: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "command: PHOTONS=$PHOTONS THICK=\"$THICK\" THETAL=\"$THETAL\" PHASE=$PHASE DEPTHS=$DEPTHS THREADS=$THREADS SEED=$SEED TAG=$TAG sh tools/slab/gen_tables.sh"
  echo "budget: $PHOTONS photons per (thickness, thetaL) run, $i runs, ke = 0.0905 m^-1, grid thetaV = 0,20,..,80,100,..,180 deg, phiV = 0,45,90,135,180 deg, $DEPTHS depths 0..t"
  echo "simulation wall time: ${sim}s on $THREADS threads; fit time: ${fit}s (training and hold-out fits in parallel)"
  echo "per-run times (from the simulation pass):"; sed 's/^/  /' "$WORK/gen_sim.log"
  echo "sha256:"
  (cd "$DATA" && sha256sum $(ls ${TAG}_fit_*.txt ${TAG}_C_tables.tar.gz ${TAG}_RT_vs_thickness.txt 2>/dev/null) | sed 's/^/  /')
} >"$DATA/${TAG}_MANIFEST.txt"
cat "$DATA/${TAG}_MANIFEST.txt"
