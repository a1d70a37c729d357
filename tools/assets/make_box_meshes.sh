#!/usr/bin/env bash
# Regenerate assets/box_19k.msh and assets/box_95k.msh (the SOFA-matching FEM benchmark box,
# config/sofa_box19k.toml and config/sofa_box95k.toml) with gmsh (Debian 12: gmsh 4.8.4, one
# thread, Delaunay 3D: deterministic for a given gmsh version).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
command -v gmsh >/dev/null || { echo "make_box_meshes: apt-get install -y gmsh" >&2; exit 1; }
gmsh -3 "$root/tools/assets/box.geo" -setnumber h 0.101 -format msh2 -nt 1 \
  -o "$root/assets/box_19k.msh" >/dev/null
gmsh -3 "$root/tools/assets/box.geo" -setnumber h 0.0584 -format msh2 -nt 1 \
  -o "$root/assets/box_95k.msh" >/dev/null
# Node and tet order along a Morton curve: ~2x faster FEM steps than gmsh's order (scattered tets).
python3 "$root/tools/assets/reorder_msh.py" "$root/assets/box_19k.msh" "$root/assets/box_95k.msh"
echo "make_box_meshes: wrote assets/box_19k.msh and assets/box_95k.msh"
