#!/usr/bin/env bash
# make.test.sh: the make interface of the study targets, rendering only one
# tiny grid (paths with spaces): a dry run (make -n) of every target of `make help` works and writes
# nothing; every study reads the same knobs (SIZE, SEEDS, SCENE, ...) and a
# name it does not read is refused, not ignored; a study without a reference
# stops before any render saying what to give. Ends with "N passed, N failed".
cd "$(dirname "$0")/.." || exit 1
source tests/lib.sh
unset MAKEFLAGS MFLAGS MAKELEVEL
R=$TMP/results

# every target `make help` lists, dry: exit 0, nothing written under RESULTS or SLURM_DIR
targets=$(make -s help | awk '$1 == "make" { print $2 }')
check "make help lists the study targets" bash -c "for t in reproduce-table rep-study caustic resolution scenes estimator-bias sweep-slurm; do
  printf '%s\n' $(echo $targets) | grep -qx \$t || { echo \"\$t missing\"; exit 1; }; done"
for t in $targets; do
  [ "$t" = sweep-slurm ] && continue
  # evaluate needs the scene it evaluates
  [ "$t" = evaluate ] && { check "make -n evaluate SCENE=tests/evaluate/box.scene: exit 0" \
    make -n evaluate SCENE=tests/evaluate/box.scene RESULTS="$R"; continue; }
  # reproducibility at its defaults (Table 1's, 1024x768): judged against
  # the POV-Ray reference, run busy with the busy loop, its renders pinned
  # to one CPU as every timed study's are (--cpu first) and by nothing else;
  # control: at 512x384 (no POV-Ray reference there) the converged
  # reference is rendered and named to the report
  if [ "$t" = reproducibility ]; then
    check "make -n reproducibility: the POV-Ray reference, the busy run's loop, pinned as every timed study" bash -c "
      out=\$(make -n reproducibility RESULTS=$R 2>&1) &&
      grep -q -- '--ref reference/cornell/cornell-reference-2x2-1024x768.exr ' <<< \"\$out\" &&
      grep -q -- '--stem [^ ]* --busy-loop ' <<< \"\$out\" &&
      grep -q -- 'experiments.launch --cpu first ' <<< \"\$out\" && ! grep -q 'taskset' <<< \"\$out\""
    check "control: make -n reproducibility SIZE=512x384 renders the converged reference and names it" bash -c "
      out=\$(make -n reproducibility SIZE=512x384 RESULTS=$R 2>&1) &&
      grep -q 'analysis.reference build .*--width 512 --height 384' <<< \"\$out\" &&
      grep -q -- '--ref $R/runs/cornell-convref-[^ ]*/512x384.exr --equal-error-a' <<< \"\$out\""
    continue
  fi
  check "make -n $t: exit 0" make -n "$t" RESULTS="$R"
done
check "make -n sweep-slurm SWEEP=reproduce-runs: exit 0, writes nothing" \
  bash -c "make -n sweep-slurm SWEEP=reproduce-runs SLURM_DIR=$TMP/dry RESULTS=$R > $TMP/dry.log 2>&1 && [ ! -e $TMP/dry ]"
check "make -n wrote nothing under RESULTS" test ! -e "$R"

# one name per knob: a study honours SIZE, SEEDS, SCENE, PHOTONS, NNS given on the command line
dry() { make -n "$@" RESULTS="$R" 2>&1; }
check "scenes SIZE=40x30 SEEDS=1: renders at 40x30, seed 1 only" \
  bash -c "out=\$(make -n scenes SIZE=40x30 SEEDS=1 SCENES=scenes/cornell.scene RESULTS=$R PHOTONS=2000 NNS=10 2>&1) &&
           grep -q -- '--width 40 --height 30 ' <<< \"\$out\" &&
           grep -q -- '--stem paper-p2000-n10/seed1 --member [^ ]*runs/cornell-40x30-s2-t1 ' <<< \"\$out\" &&
           ! grep -q 'seed2' <<< \"\$out\""
check "caustic SIZE=40x30 SEEDS=2 NNS=10: the caustic scene at 40x30" \
  bash -c "dry() { make -n caustic SIZE=40x30 SEEDS=2 NNS=10 PHOTONS=2000 REF=reference/caustic/caustic-reference-128x96.exr RESULTS=$R 2>&1; };
           out=\$(dry) && grep -q -- '--stem paper-p2000-n10/seed2 --member [^ ]*runs/caustic-40x30-s2-t1 ' <<< \"\$out\" && ! grep -q 'seed3' <<< \"\$out\""
check "estimator-bias SEEDS=2 NNS=5: those seeds and n only" \
  bash -c "out=\$(make -n estimator-bias SEEDS=2 NNS=5 RESULTS=$R 2>&1) && grep -q 'experiments.launch .*--stem paper-p50000-n5/seed2 --member [^ ]*/runs/estimator-bias ' <<< \"\$out\" &&
           ! grep -q -- '-n10/' <<< \"\$out\" && ! grep -q 'seed3' <<< \"\$out\""
# gather: cornell at SIZE and at GATHER_CORNELL_SIZES, one run root per N
# (gatherN), the heavy conventional renders once (12,288 eye samples x 8 x 40
# >= ONE_REPEAT_WORK; 4 x 10 is not, nor 32x24's 3,072 x 8 x 40), the scenes study's runs as the map seen
# directly, TIME_REPEATS from the environment
check "gather: the grids per case and N, one_repeat, the scenes study's runs, TIME_REPEATS from the environment" \
  bash -c "out=\$(TIME_REPEATS=3 make -n gather SIZE=64x48 SEEDS=2 SCENES=scenes/cornell.scene GATHERS='4 8' GATHER_CORNELL_SIZES=32x24 \
             PHOTONS=5000 NNS='10 40' ONE_REPEAT_WORK=3e6 RESULTS=$R 2>&1) &&
           grep -q -- '--repeats 3 --of 8 --stem paper-p5000-n40/seed1 --member [^ ]*runs/cornell-64x48-s2-t1-gather8 conventional .--gather 8 --direct shadow-rays. 3 --member-repeats [^ ]*-gather8 conventional 1 ' <<< \"\$out\" &&
           grep -- 'n10/seed1 --member [^ ]*cornell-64x48-s2-t1-gather4 ' <<< \"\$out\" | grep -q -- '--repeats 3 ' &&
           ! grep -- 'n10/seed1 --member [^ ]*cornell-64x48-s2-t1-gather4 ' <<< \"\$out\" | grep -q -- --member-repeats &&
           grep -q 'analysis.reference build .*--width 32 --height 24' <<< \"\$out\" &&
           grep -q -- '--grid scenes/cornell.scene 32x24 8 [^ ]*/gather/runs-cornell-32x24-N8.csv' <<< \"\$out\" &&
           grep -q -- '--direct scenes/cornell.scene 64x48 [^ ]*/scenes/runs-cornell.csv' <<< \"\$out\""
check "resolution SIZE=40x30: that size only" \
  bash -c "out=\$(make -n resolution SIZE=40x30 SEEDS=1 PHOTONS=2000 NNS=10 RESULTS=$R 2>&1) && grep -q 'convref.*/40x30.exr' <<< \"\$out\" &&
           ! grep -q '256x192' <<< \"\$out\""
for old in SCENES_SIZE=128x96 SCENES_SEEDS=2 CAUSTIC_SIZE=64x48 CAUSTIC_SEEDS=2 BIAS_SEEDS=3 REP_SEEDS=2 RES_SEEDS=2 EE_TIME=total_s WIDTH=64; do
  check "a name no target reads is refused: $old" expect_exit 2 "${old%%=*} is gone: every study target reads" make -n scenes "$old"
done
check "scenes refuses SCENE= (it runs every scene of SCENES)" expect_exit 2 "give SCENES=" make -n scenes SCENE=scenes/slabs.scene
check "resolution refuses REF= (it takes RES_REF=ours or pov)" expect_exit 2 "RES_REF" make -n resolution REF=x.exr
check "SIZE=0x0 and SEEDS=abc are refused" bash -c "
  ! make -n reproduce-runs SIZE=0x0 > $TMP/s.log 2>&1 && grep -q 'SIZE=0x0: not WxH' $TMP/s.log &&
  ! make -n reproduce-runs SEEDS=abc > $TMP/e.log 2>&1 && grep -q 'SEEDS=abc: a positive number' $TMP/e.log"
check "SIZE=99999x1 is refused with the renderer's range (16384x1 is not)" bash -c "
  ! make -n reproduce-runs SIZE=99999x1 REF=x.exr > $TMP/w.log 2>&1 && grep -q 'SIZE=99999x1: each side must be at most 16384' $TMP/w.log &&
  make -n reproduce-runs SIZE=16384x1 REF=x.exr > /dev/null 2>&1"
mkdir -p "$TMP/sp ace"
cp scenes/cornell.scene "$TMP/sp ace/my room.scene"
check "a SCENE path with a space works: the engine's dry run names its run root (control: a missing one is refused)" bash -c "
  make -n reproduce-runs SCENE='$TMP/sp ace/my room.scene' REF=x.exr > $TMP/sp.log 2>&1 &&
  grep -q 'runs/my room-1024x768-s2-t1/' $TMP/sp.log &&
  ! make -n evaluate SCENE='$TMP/sp ace/no room.scene' > $TMP/sp2.log 2>&1 && grep -q 'no room.scene: no such file' $TMP/sp2.log"

# per-pixel metrics at the paper's size are judged against the POV-Ray
# reference with the renders' own 2x2 subpixel rays, its floor from the fast
# preset of the same sampling; never the one-sample reference (block metrics only)
check "reproduce-table's default reference and floor at 1024x768 are the 2x2 renders, not the one-sample ones" bash -c "
  out=\$(make -n reproduce-table RESULTS=$R 2>&1) &&
  grep -q -- '--ref reference/cornell/cornell-reference-2x2-1024x768.exr ' <<< \"\$out\" &&
  grep -q -- '--ref-fast reference/cornell/cornell-fast-2x2-1024x768.exr ' <<< \"\$out\" &&
  ! grep -q 'cornell-reference-1024x768\|cornell-fast-1024x768' <<< \"\$out\""
# studies.pov_reference on a tree of empty files: the 2x2 pair wins over the one-sample
# pair; control: with the one-sample pair alone it is found (the check above
# tells them apart), and a pbrt or bounce-limited render is never a POV-Ray reference
fr="$TMP/povref"; mkdir -p "$fr/a/reference/cornell" "$fr/b/reference/cornell" "$fr/c/reference/tworooms"
for f in reference-1024x768 fast-1024x768 reference-2x2-1024x768 fast-2x2-1024x768; do : > "$fr/a/reference/cornell/cornell-$f.exr"; done
for f in reference-1024x768 fast-1024x768; do : > "$fr/b/reference/cornell/cornell-$f.exr"; done
: > "$fr/c/reference/tworooms/tworooms-pbrt-bdpt-256x192-seed1.exr"; : > "$fr/c/reference/tworooms/tworooms-b2-reference-256x192.exr"
# povref TOP SIZE SCENE [fast]: the reference studies.pov_reference names in TOP
povref() { "${PYTHON:-/usr/bin/python3}" -c "import sys; from experiments.studies import pov_reference as p; print(p(sys.argv[2], sys.argv[3], fast=len(sys.argv) > 4, top=sys.argv[1]))" "$@"; }
check "pov_reference prefers the 2x2 reference and pairs it with the 2x2 fast render" \
  test "$(povref $fr/a 1024x768 scenes/cornell.scene)|$(povref $fr/a 1024x768 scenes/cornell.scene fast)" = \
  "reference/cornell/cornell-reference-2x2-1024x768.exr|reference/cornell/cornell-fast-2x2-1024x768.exr"
check "control: pov_reference without the 2x2 pair names the one-sample pair" \
  test "$(povref $fr/b 1024x768 scenes/cornell.scene)|$(povref $fr/b 1024x768 scenes/cornell.scene fast)" = \
  "reference/cornell/cornell-reference-1024x768.exr|reference/cornell/cornell-fast-1024x768.exr"
check "pov_reference never names a pbrt or bounce-limited render" test -z "$(povref $fr/c 256x192 scenes/tworooms.scene)"

# a scene without a reference: stop before rendering, say what to give
cp scenes/cornell.scene "$TMP/my.scene"
make reproduce-table SCENE="$TMP/my.scene" SIZE=32x24 PHOTONS=2000 NNS=10 SEEDS=1 RESULTS="$R" > "$TMP/noref.log" 2>&1; rc=$?
check "reproduce-table without a reference: exit non-zero, says REF= or make scenes, renders nothing" \
  bash -c "[ $rc -ne 0 ] && grep -q 'no reference' $TMP/noref.log && grep -q 'give REF=' $TMP/noref.log &&
           grep -q 'make scenes SCENES=' $TMP/noref.log && [ ! -e $R/runs ]"
make -n reproduce-table SCENE="$TMP/my.scene" SIZE=32x24 REF="$TMP/my.exr" RESULTS="$R" > "$TMP/ref.log" 2>&1; rc=$?
check "reproduce-table with REF=: runs (dry)" bash -c "[ $rc -eq 0 ] && grep -q 'runs/my-32x24-s2-t1 ' $TMP/ref.log"
# paths with spaces: a scene, its reference and RESULTS in folders with a
# space, rendered and analysed end to end (a tiny grid, one repeat)
SP="$TMP/sp ace"; mkdir -p "$SP"; cp scenes/cornell.scene "$SP/my room.scene"
build/photonmap render "$SP/my room.scene" --width 16 --height 12 --photons 20000 --nn 50 --quiet -o "$SP/ref.exr"
make reproduce-table SCENE="$SP/my room.scene" SIZE=16x12 SEEDS=2 PHOTONS="2000 4000" NNS=10 REF="$SP/ref.exr" \
  RESULTS="$SP/results" TIME_REPEATS=1 BOOTSTRAP=200 > "$TMP/space.log" 2>&1; rc=$?
check "reproduce-table with spaces in SCENE, REF and RESULTS: exit 0, the table and 16 renders written" bash -c '
  [ "$1" -eq 0 ] && [ -s "$2/table1/table1.md" ] && [ "$(ls "$2"/runs/*/*/seed*.run.json | wc -l)" -eq 16 ]' _ "$rc" "$SP/results"
finish
