#!/bin/sh
# Shell tests of the cumulo-slab CLI: output formats, argument errors (exit 2), determinism across thread counts, Mie tables.
. tests/lib.sh
S=build/cumulo-slab
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

out=$($S --phase hg:0.85 --tau 10 --mu0 0.5 --photons 1e4 --report totals --quiet)
if printf '%s\n' "$out" | grep -Eq '^R 0\.[0-9]{5} \+- 0\.[0-9]{5}$' && printf '%s\n' "$out" | grep -Eq '^T 0\.[0-9]{5} \+- 0\.[0-9]{5}$' \
   && [ "$(printf '%s\n' "$out" | wc -l)" -eq 2 ]; then t_ok totals_format; else t_fail totals_format "got: $out"; fi

out=$($S --phase hg:0.85 --tau 10 --mu0 0.5 --photons 1e4 --report radiance --mu 1,0.5,0.2 --quiet)
if printf '%s\n' "$out" | grep -Eq '^reflect mu=0\.5 [0-9]+\.[0-9]{4} \+- [0-9]+\.[0-9]{4}$' \
   && printf '%s\n' "$out" | grep -Eq '^transmit mu=0\.2 [0-9]+\.[0-9]{4} \+- [0-9]+\.[0-9]{4}$' \
   && [ "$(printf '%s\n' "$out" | wc -l)" -eq 6 ]; then t_ok radiance_format; else t_fail radiance_format "got: $out"; fi

a=$($S --tau 3 --mu0 0.6 --photons 2e4 --report totals,orders,radiance --mu 0.7 --threads 2 --seed 9 --quiet)
b=$($S --tau 3 --mu0 0.6 --photons 2e4 --report totals,orders,radiance --mu 0.7 --threads 2 --seed 9 --quiet)
c=$($S --tau 3 --mu0 0.6 --photons 2e4 --report totals,orders,radiance --mu 0.7 --threads 1 --seed 9 --quiet)
[ "$a" = "$b" ] && t_ok same_seed_same_output || t_fail same_seed_same_output "outputs differ"
[ "$a" = "$c" ] && t_ok thread_count_independent || t_fail thread_count_independent "1 vs 2 threads differ"

t_expect bad_tau 2 "optical thickness" -- $S --tau -1
t_expect no_tau 2 "exactly one of --tau or --thickness" -- $S --photons 10
t_expect both_tau 2 "exactly one of --tau or --thickness" -- $S --tau 1 --thickness 100
t_expect bad_mu0 2 "--mu0" -- $S --tau 1 --mu0 1.5
t_expect bad_phase 2 "--phase" -- $S --tau 1 --phase foo
t_expect bad_hg 2 "-1 < G < 1" -- $S --tau 1 --phase hg:1.2
t_expect bad_number 2 "expects a number" -- $S --tau 1x
t_expect bad_option 2 "unknown option" -- $S --tau 1 --frobnicate 3
t_expect bad_report 2 "unknown report" -- $S --tau 1 --report everything
t_expect radiance_needs_mu 2 "--mu" -- $S --tau 1 --report radiance
t_expect bad_mu 2 "--mu values" -- $S --tau 1 --report radiance --mu 0,0.5
# an unreadable table is a failure of the run, not of the arguments: exit 1 (it was 2 before exit codes were split)
t_expect missing_mie 1 "cannot open Mie table" -- $S --tau 1 --phase mie:/nonexistent/table.txt
t_expect grazing_table 2 "not within 1 deg of 90" -- $S --tau 1 --report table --thetav 0,90
t_expect missing_value 2 "--tau needs a value" -- $S --tau
t_expect stray_argument 2 "unexpected argument 'stray'" -- $S --tau 1 stray
t_expect unwritable_out 1 "cannot write '/nonexistent/C.txt'" -- $S --tau 1 --photons 100 --report table --depths 2 \
  --out /nonexistent/C.txt --quiet
mkdir -p build/test-output; ln -sf /dev/full build/test-output/slab_full.txt
t_expect table_onto_full_disk 1 "build/test-output/slab_full.txt" -- $S --tau 1 --photons 100 --report table --depths 2 \
  --out build/test-output/slab_full.txt --quiet
t_expect threads_overflow 2 "--threads" -- $S --tau 1 --threads 4294967297
t_expect seed_not_exact 2 "--seed" -- $S --tau 1 --seed 9007199254740993.5
t_expect depths_overflow 2 "--depths" -- $S --tau 1 --depths 4294967297
t_expect sphere_seed_not_exact 2 "--seed" -- build/cumulo-slab-sphere --diameter 100 --seed 9007199254740993.5

# --help describes every option on stdout and --version names the release, for the three slab programs
t_help_version cumulo-slab $S --tau --thickness --ke --mu0 --phase --photons --threads --seed --batches --report \
  --mu --phi --depths --thetav --phiv --out --quiet --help --version
F=build/cumulo-slab-fit
t_help_version cumulo-slab-fit $F --model --holdout --frac --out --predict --help --version
t_expect fit_no_table 2 "no TABLE given" -- $F --model bouthors
t_expect fit_missing_value 2 "--model: needs a value" -- $F --model
t_expect fit_bad_frac 2 "--frac" -- $F --frac 2 x.txt
t_expect fit_unknown 2 "--bogus: unknown option" -- $F --bogus
t_expect fit_missing_table 1 "cannot open table" -- $F /nonexistent/C.txt
P=build/cumulo-slab-sphere
t_help_version cumulo-slab-sphere $P --diameter --ke --phase --photons --seed --help --version
t_expect sphere_no_diameter 2 "--diameter: is required" -- $P --photons 10
t_expect sphere_missing_value 2 "--diameter: needs a value" -- $P --diameter
t_expect sphere_bad_number 2 "--ke: expects a number" -- $P --diameter 100 --ke 1x
t_expect sphere_unknown 2 "--bogus: unknown option" -- $P --diameter 100 --bogus
t_expect sphere_missing_mie 1 "cannot open Mie table" -- $P --diameter 100 --phase mie:/nonexistent/table.txt

# a Mie-format table generated from HG g = 0.85 (no chop): same R as --phase hg:0.85 within errors
awk 'BEGIN { g = 0.85; pi = 3.14159265358979; print "# HG 0.85 in Mie-table format"; print "channels 3";
  print "lambda_nm 680 550 440"; print "sigma_ext_um2 113 113 113"; print "g 0.85 0.85 0.85"; print "chop_deg 0";
  print "f 0 0 0"; print "angles 721";
  for (i = 0; i <= 720; i++) { th = i / 4; c = cos(th * pi / 180); p = (1 - g * g) / (4 * pi * (1 + g * g - 2 * g * c) ^ 1.5);
    printf "%.4f %.9e %.9e %.9e\n", th, p, p, p } }' >"$tmp/hg.tbl"
m=$($S --phase "mie:$tmp/hg.tbl:g" --tau 5 --photons 1e5 --quiet --seed 3 | awk '/^R /{print $2, $4}')
h=$($S --phase hg:0.85 --tau 5 --photons 1e5 --quiet --seed 4 | awk '/^R /{print $2, $4}')
if echo "$m $h" | awk '{ d = $1 - $3; if (d < 0) d = -d; exit !(d < 3 * sqrt($2 * $2 + $4 * $4)) }'; then t_ok mie_table_transport
else t_fail mie_table_transport "R(table)=$m R(hg)=$h"; fi

# MPI build (only when mpicc was found at build time): 2 ranks reproduce the threaded output bit for bit
if [ -x build/cumulo-slab-mpi ] && command -v mpirun >/dev/null 2>&1; then
  A="--tau 3 --mu0 0.6 --photons 2e4 --report totals,orders,radiance,table --depths 3 --mu 0.7 --seed 9 --quiet --threads 1"
  m=$(timeout 120 mpirun --allow-run-as-root --oversubscribe -np 2 build/cumulo-slab-mpi $A 2>/dev/null)
  s=$($S $A)
  if [ -n "$m" ] && [ "$m" = "$s" ]; then t_ok mpi_same_results; else t_fail mpi_same_results "MPI output differs or empty"; fi
else
  t_skip mpi_same_results "build/cumulo-slab-mpi or mpirun not available"
fi

# data/slab_*: every file listed in the manifest's sha256 section matches (regenerate the manifest with gen_tables.sh)
if [ -f data/slab_MANIFEST.txt ]; then
  sums=$(sed -n '/^sha256:/,$p' data/slab_MANIFEST.txt | sed 1d | sed 's/^ *//')
  if [ -n "$sums" ] && bad=$(cd data && printf '%s\n' "$sums" | sha256sum -c --quiet 2>&1); then t_ok data_checksums
  else t_fail data_checksums "manifest sha256 mismatch: ${bad:-no sha256 lines}"; fi
else
  t_fail data_checksums "data/slab_MANIFEST.txt missing"
fi
# the renderer loads data/slab_fit_bouthors.txt by (name, group, t_m, node): that key list (every field but the value)
# must not change, and neither must the log-separable file's
# (7 thicknesses 25..1600 m, 8 groups, P* on 15 deg nodes, A1/B1/C/D on 10 thetaV nodes, A2/B2 on thetaL 0,30,50,70)
k=$(awk '!/^#/ { $NF = ""; print }' data/slab_fit_bouthors.txt | sha256sum | cut -d' ' -f1)
[ "$k" = 1e80eec5b0866507cd7e569631969b2dcefb52eacb394ad95f2516148cc0608e ] && t_ok bouthors_table_layout \
  || t_fail bouthors_table_layout "key list (name group t_m node) changed: $k"
k=$(awk '!/^#/ { $NF = ""; print }' data/slab_fit_logsep.txt | sha256sum | cut -d' ' -f1)
[ "$k" = 7f993a509ea860ae0c7b2bfcc16e6b1d3205f05edb43e22c017d4f805b78f19c ] && t_ok logsep_table_layout \
  || t_fail logsep_table_layout "key list (name group t_m d/t angle) changed: $k"
if awk '!/^#/ && $NF !~ /^-?[0-9]+(\.[0-9]*)?([eE][-+]?[0-9]+)?$/ { bad = 1 } END { exit bad }' \
     data/slab_fit_bouthors.txt data/slab_fit_logsep.txt; then t_ok fit_tables_finite
else t_fail fit_tables_finite "non-numeric or non-finite value in data/slab_fit_*.txt"; fi
# the renderer (src/core/slabmodel.c) takes logarithms of P, A1, A2, C, D: they must be positive (B1, B2 may be any sign)
if awk '!/^#/ && $1 != "B1" && $1 != "B2" && !($5 > 0) { bad = 1 } END { exit bad }' data/slab_fit_bouthors.txt
then t_ok bouthors_positive; else t_fail bouthors_positive "non-positive P/A1/A2/C/D in data/slab_fit_bouthors.txt"; fi

t_summary
