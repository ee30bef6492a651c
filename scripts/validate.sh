#!/usr/bin/env bash
# Full-size validation runs (not part of CI): the figures and tables of the seeds.
# Writes everything under out/validation/. Takes about 90 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cargo build --release -p gsph
g=target/release/gsph

echo "== the full-size tests CI leaves out (#[ignore = \"full size: make validate\"])"
cargo test -p gsph-tests --release -- --ignored
o=out/validation
mkdir -p "$o"

echo "== seed 000 table 2: energy error of each scheme on the flyer plate"
$g study cases/flyer_plate.toml --schemes av,pm,ts1,ts2 --resolutions 1 --metric energy_rel_error --out "$o/energy_table"
for s in av pm ts1 ts2; do
  $g run cases/flyer_plate.toml --set scheme=$s --out "$o/flyer_$s" --quiet
  $g plot profile "$o/flyer_$s"
done

echo "== seed 004 fig 2b (1D): L1(sigma_xx) against resolution, elastic-plastic Riemann problem"
$g study cases/riemann_al.toml --schemes av,pm,ts1,ts2 --resolutions 1,2,4,8 --out "$o/riemann_study"

echo "== seed 000 §4.2: collapsing ring, ts2 at 8,172 and 23,780 particles"
for r in 1 1.7127; do
  d="$o/ring_ts2_$r"
  $g run cases/ring_collapse.toml --set resolution_scale=$r --out "$d"
  $g plot particles "$d" --field eps_p
  $g plot particles "$d" --field tau_xy
  $g plot series "$d" --columns inner_radius,outer_radius,inner_radius_exact,outer_radius_exact --y-label "radius (m)"
done
for s in ts1 av; do
  d="$o/ring_${s}_1"
  # the scene asks for the two-shock solver, which av does not have
  unset_riemann=(); [[ $s == av ]] && unset_riemann=(--unset options.riemann)
  $g run cases/ring_collapse.toml --set scheme=$s "${unset_riemann[@]}" --out "$d"
  $g plot particles "$d" --field eps_p
done

echo "== seed 004 fig 2b: L1(sigma_xx) against particles along x, 2D Riemann problem, pm vs tkc"
$g study cases/riemann_al_2d.toml --schemes pm,tkc --resolutions 1,2,4,8 --out "$o/riemann_2d_study"
for s in pm tkc; do
  $g run cases/riemann_al_2d.toml --set scheme=$s --set resolution_scale=2 --out "$o/riemann_2d_$s" --quiet
  $g plot profile "$o/riemann_2d_$s"
done

echo "== seed 004 fig 3b: L1(U_x) against particles, sound wave, pm vs tkc (1D and 2D)"
$g study cases/sound_cu.toml --schemes pm,tkc --resolutions 0.5,1,2,4 --out "$o/sound_study"
$g study cases/sound_cu_2d.toml --schemes pm,tkc --resolutions 0.5,1,2 --out "$o/sound_2d_study"

echo "== seed 004 fig 5: Verney stopping radius against particle size, pm vs tkc"
$g study cases/verney_al.toml --schemes pm,tkc --resolutions 0.5,1,2 --metric inner_radius --out "$o/verney_study"
$g run cases/verney_al.toml --set resolution_scale=2 --out "$o/verney_tkc_2"
$g plot particles "$o/verney_tkc_2" --field von_mises
$g plot series "$o/verney_tkc_2" --columns inner_radius,inner_radius_exact --y-label "radius (m)"
echo "== seed 000 §5: steel -> SiC impact (51,200 particles, 15 us), av, ts1, ts2, tkc, pm; damage and v_x at 5, 10, 15 us"
for s in av ts1 ts2 tkc pm; do
  d="$o/impact_$s"
  unset_riemann=(); [[ $s == av ]] && unset_riemann=(--unset options.riemann)
  $g run cases/steel_sic_impact.toml --set scheme=$s "${unset_riemann[@]}" --out "$d" --quiet
  for t in 5e-6 1e-5 1.5e-5; do
    $g plot particles "$d" --field damage --time $t --highlight-material 0 --range 0,1 --out "$d/damage_$t.png"
    $g plot particles "$d" --field vx --time $t --highlight-material 0 --out "$d/vx_$t.png"
  done
  $g plot series "$d" --columns back_face_velocity --y-label "back-face v_x (m/s)"
done

echo "== 3D steel -> SiC impact (50,000 particles), every scheme"
for s in av pm ts1 ts2 tkc; do
  unset_riemann=(); [[ $s == av ]] && unset_riemann=(--unset options.riemann)
  $g run cases/steel_sic_impact_3d.toml --set scheme=$s "${unset_riemann[@]}" --out "$o/impact_3d_$s" --quiet
done
echo "== seed 004 §3-4: Hugoniot of porous copper from the moving window (2 um spacing)"
$g hugoniot cases/porous_cu_window.toml --up 50,75,100,125,150,200 --set resolution_scale=0.5 --out "$o/hugoniot_2um"
echo "== seed 004 §4 (cross-check of the moving window): piston-driven compaction of porous copper, u_p = 100 m/s, 2 mm sample"
$g run cases/porous_cu_piston.toml --set resolution_scale=0.5 --out "$o/porous_piston_2um" --quiet
$g run cases/porous_cu_piston.toml --out "$o/porous_piston" --quiet
$g plot series "$o/porous_piston" --columns front_position --y-label "front (m)"
$g plot particles "$o/porous_piston" --field vx
echo "validation outputs in $o"
