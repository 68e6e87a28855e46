#!/bin/sh
# Generates the slab C tables with build/cumulo-slab, fits them with build/cumulo-slab-fit, writes data/slab_* + manifest.
# Usage (from the repo root): sh tools/slab/gen_tables.sh   (environment overrides below)
# Default budget: chopped Mie phase function (data/mie_cloud.tbl, green channel), 3e5 photons per (t, thetaL) run,
# 28 runs, eq. 3.32 + log-separable fits (training and phi_V = 90 hold-out). Measured: 2219 s simulation + 1041 s fits
# = 54 min under nice -n 10 on the shared 2-core machine (load average 4-8 from other jobs); less on an idle machine.
# Share the machine politely with: nice -n 10 sh tools/slab/gen_tables.sh
set -eu
PHOTONS=${PHOTONS:-3e5}
THICK=${THICK:-"25 50 100 200 400 800 1600"}
THETAL=${THETAL:-"0 30 50 70"}
PHASE=${PHASE:-mie:data/mie_cloud.tbl:g}
DEPTHS=${DEPTHS:-11}
THREADS=${THREADS:-2}
SEED=${SEED:-1000}
WORK=${WORK:-build/slab_tables}
DATA=${DATA:-data}
TAG=${TAG:-slab}
SLAB=${SLAB:-build/cumulo-slab}
FIT=${FIT:-build/cumulo-slab-fit}
NOTE=${NOTE:-}
mkdir -p "$WORK" "$DATA" "$WORK/bin"
# Snapshot the binaries and the phase table, so that a rebuild or a new Mie table during the run cannot mix versions.
cp "$SLAB" "$WORK/bin/cumulo-slab"; cp "$FIT" "$WORK/bin/cumulo-slab-fit"
SLAB=$WORK/bin/cumulo-slab; FIT=$WORK/bin/cumulo-slab-fit
PHASE_RUN=$PHASE; PHASE_SUM=""
case "$PHASE" in mie:*)
  pf=${PHASE#mie:}; ch=""
  case "$pf" in *:[rgb]) ch=${pf##*:}; pf=${pf%:*} ;; esac
  cp "$pf" "$WORK/phase_mie.tbl"
  PHASE_SUM="$(sha256sum <"$WORK/phase_mie.tbl" | cut -d' ' -f1)  $pf (copied to $WORK/phase_mie.tbl for the run)"
  PHASE_RUN="mie:$WORK/phase_mie.tbl${ch:+:$ch}" ;;
esac
start=$(date +%s)
load0=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)
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
    "$SLAB" --thickness "$t" --mu0 "$mu" --phase "$PHASE_RUN" --photons "$PHOTONS" --threads "$THREADS" \
      --seed "$s" --depths "$DEPTHS" --report table --out "$f" --quiet
    echo "t=$t thetaL=$L seed=$s $(( $(date +%s) - t0 ))s" | tee -a "$log"
  done
done
sim=$(( $(date +%s) - start ))
if [ -z "$THICK" ]; then sim="(not re-run; see the per-run log)"; else cp "$log" "$WORK/gen_sim.log"; fi
t0=$(date +%s)
# eq. 3.32 and the log-separable form; the training and hold-out fits of one model are independent, so they run side
# by side (2 cores), one model after the other.
# (logsep2 -- P* also depending on depth -- has ~300 parameters per slice and takes ~30 s per slice: --model logsep2)
MODELS=${MODELS:-"bouthors logsep"}
fitlog=""
case " $STAGES " in *" fit "*)
  for m in $MODELS; do
    tm=$(date +%s)
    "$FIT" --model "$m" --out "$DATA/${TAG}_fit" "$WORK"/C_t*_L*.txt >"$DATA/${TAG}_fit_report_$m.txt" &
    "$FIT" --model "$m" --holdout "$WORK"/C_t*_L*.txt >"$DATA/${TAG}_fit_holdout_$m.txt"
    wait
    fitlog="$fitlog $m $(( $(date +%s) - tm ))s;"
    echo "fit $m $(( $(date +%s) - tm ))s"
  done ;;
esac
fit=$(( $(date +%s) - t0 ))
load1=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)
# raw tables, compressed, so the fit can be redone without re-simulating
tar -C "$WORK" -czf "$DATA/${TAG}_C_tables.tar.gz" $(cd "$WORK" && ls C_t*_L*.txt)
{
  echo "# slab tables manifest (tools/slab/gen_tables.sh)"
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)  git: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "command: PHOTONS=$PHOTONS THICK=\"$THICK\" THETAL=\"$THETAL\" PHASE=$PHASE DEPTHS=$DEPTHS THREADS=$THREADS SEED=$SEED TAG=$TAG sh tools/slab/gen_tables.sh"
  echo "  i.e. per run k: cumulo-slab --thickness t --mu0 cos(thetaL) --phase $PHASE --photons $PHOTONS --threads $THREADS --seed $SEED+k --depths $DEPTHS --report table --out $WORK/C_tTTTTT_LLL.txt --quiet"
  [ -n "$PHASE_SUM" ] && echo "phase table sha256: $PHASE_SUM"
  echo "budget: $PHOTONS photons per (thickness, thetaL) run, $i runs, ke = 0.0905 m^-1, grid thetaV = 0,20,..,80,100,..,180 deg, phiV = 0,45,90,135,180 deg, $DEPTHS depths 0..t, 100 batches"
  echo "niceness: $(nice)  load average (1, 5, 15 min) at start: $load0, at end: $load1"
  echo "simulation wall time: ${sim}s on $THREADS threads; fit time: ${fit}s (per model, training and hold-out side by side:$fitlog)"
  [ -n "$NOTE" ] && echo "note: $NOTE"
  echo "per-run times (from the simulation pass):"; sed 's/^/  /' "$WORK/gen_sim.log"
  echo "raw tables: ${TAG}_C_tables.tar.gz (refit with: tar -C $WORK -xzf $DATA/${TAG}_C_tables.tar.gz; STAGES=\"fit manifest\" sh tools/slab/gen_tables.sh)"
  echo "sha256:"
  (cd "$DATA" && sha256sum $(ls ${TAG}_fit_*.txt ${TAG}_C_tables.tar.gz ${TAG}_RT_vs_thickness.txt ${TAG}_RT_crossover.txt \
    ${TAG}_sphere_updown.txt 2>/dev/null) | sed 's/^/  /')
} >"$DATA/${TAG}_MANIFEST.txt"
cat "$DATA/${TAG}_MANIFEST.txt"
