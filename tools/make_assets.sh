#!/usr/bin/env bash
# Regenerate Serosa's organ and validation meshes in assets/ (Gmsh 2.2 ASCII, metres).
#
#   tools/make_assets.sh [coarse|fine|beam|all]     (default: all)
#
# The meshes are committed, so building Serosa needs no mesher; run this only
# to change them. Needs python3 and, for the organs, gmsh with OpenCASCADE:
#   apt-get install -y gmsh tetgen        (Debian 12: gmsh 4.8.4)
# Deterministic: fixed sizes and options, one thread, Delaunay 3D. The output
# is reproducible with the same gmsh version (4.8.4 made the committed files);
# another version gives valid but different meshes.
# Meshers run one at a time. After meshing, tools/assets/check_msh.py checks
# every file (positive tets, conformity, quality) and assets/README.md is
# rewritten with its report.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
src="$root/tools/assets"
out="$root/assets"
what="${1:-all}"
case "$what" in coarse|fine|beam|all) ;; *) echo "usage: $0 [coarse|fine|beam|all]" >&2; exit 2 ;; esac

command -v python3 >/dev/null || { echo "make_assets: python3 is required" >&2; exit 1; }
need_gmsh=0
[ "$what" != beam ] && need_gmsh=1
if [ $need_gmsh = 1 ]; then
  if ! command -v gmsh >/dev/null; then
    echo "make_assets: gmsh not found; install it with: apt-get install -y gmsh tetgen" >&2
    exit 1
  fi
  ver="$(gmsh --version 2>&1 | tail -n 1)"
  if [ "$ver" != "4.8.4" ]; then
    echo "make_assets: warning: gmsh $ver (committed meshes were made with 4.8.4); meshes will differ" >&2
  fi
fi

mkdir -p "$out"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# gmsh GEO NAME [-setnumber var value ...]: mesh to $tmp then move into assets/
mesh() {
  local geo="$1" name="$2"; shift 2
  echo "== $name.msh"
  if ! gmsh -3 "$src/$geo" -format msh2 -nt 1 -o "$tmp/$name.msh" "$@" >"$tmp/$name.log" 2>&1; then
    cat "$tmp/$name.log" >&2; echo "make_assets: gmsh failed on $name" >&2; exit 1
  fi
  grep -E "^(Warning|Error)" "$tmp/$name.log" >&2 || true
  mv "$tmp/$name.msh" "$out/$name.msh"
}

beam() {
  python3 "$src/make_beam.py" "$1" "$2" "$3" "$out/$4.msh" "${@:5}"
}

if [ "$what" = beam ] || [ "$what" = all ]; then
  beam 10 1 1 beam_xcoarse
  beam 20 2 2 beam_coarse
  beam 40 4 4 beam_fine
  # the transfer drill's bead: 12 x 6 x 6 mm on the board (z = 0), at its start on the left
  beam 6 3 3 bead --size 0.012 0.006 0.006 --corner -0.031 -0.003 0.0 --name bead
fi
if [ "$what" = coarse ] || [ "$what" = all ]; then
  mesh appendectomy.geo appendectomy_coarse \
    -setnumber h_cecum 0.008 -setnumber h_appendix 0.0035 -setnumber h_meso 0.0025 -setnumber curvature 8
  mesh liver.geo liver_coarse -setnumber h 0.010 -setnumber curvature 10
fi
if [ "$what" = coarse ] || [ "$what" = all ]; then
  # The default scene's: refined round the base, the artery tagged in the mesoappendix.
  mesh appendectomy.geo appendectomy_procedure \
    -setnumber h_cecum 0.008 -setnumber h_appendix 0.0035 -setnumber h_meso 0.0025 -setnumber curvature 8 \
    -setnumber h_base 0.0022
  python3 "$src/tag_artery.py" "$out/appendectomy_procedure.msh"
  python3 "$src/reorder_msh.py" "$out/appendectomy_procedure.msh"
fi
if [ "$what" = fine ] || [ "$what" = all ]; then
  mesh appendectomy.geo appendectomy_fine \
    -setnumber h_cecum 0.0032 -setnumber h_appendix 0.0015 -setnumber h_meso 0.0011 -setnumber curvature 16
  mesh liver.geo liver_fine -setnumber h 0.004 -setnumber curvature 16
  # The fine scene's whole procedure: the default scene's anatomy at the fine sizes, the cecum
  # (which nothing cuts) a little coarser, the base finer than the appendix (about 29k tets).
  mesh appendectomy.geo appendectomy_procedure_fine \
    -setnumber h_cecum 0.0045 -setnumber h_appendix 0.0015 -setnumber h_meso 0.0011 -setnumber curvature 16 \
    -setnumber h_base 0.0011
  python3 "$src/tag_artery.py" "$out/appendectomy_procedure_fine.msh"
  python3 "$src/reorder_msh.py" "$out/appendectomy_procedure_fine.msh"
fi

# check everything present and rewrite the README's report
cd "$root"
files=()
for f in appendectomy_coarse appendectomy_procedure appendectomy_fine appendectomy_procedure_fine liver_coarse liver_fine beam_xcoarse beam_coarse beam_fine bead; do
  [ -f "assets/$f.msh" ] && files+=("assets/$f.msh")
done
status=0
python3 "$src/check_msh.py" --min-quality 0.2 "${files[@]}" >"$tmp/report.txt" || status=$?
cat "$tmp/report.txt"
python3 - "$out/README.md" "$tmp/report.txt" <<'PY'
import sys
readme, report = sys.argv[1], open(sys.argv[2]).read()
begin, end = "<!-- check_msh report: begin -->", "<!-- check_msh report: end -->"
text = open(readme).read() if __import__("os").path.exists(readme) else ""
block = begin + "\n```\n" + report + "```\n" + end
if begin in text and end in text:
    text = text[:text.index(begin)] + block + text[text.index(end) + len(end):]
else:
    text = text.rstrip("\n") + "\n\n" + block + "\n"
open(readme, "w").write(text)
PY
[ $status = 0 ] || { echo "make_assets: check_msh.py found problems" >&2; exit $status; }
echo "make_assets: done"
