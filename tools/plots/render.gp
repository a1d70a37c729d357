# Rendering benchmarks (docs/BENCHMARKS.md "Rendering"), from the CSVs of serosa_bench_render
# (one file per benchmark: Google Benchmark's CSV wants the same counters in every row):
#   B=build/<dir>/bench/serosa_bench_render
#   $B --benchmark_filter=FrameTime --benchmark_min_time=0.1 --benchmark_format=csv \
#       > docs/plots/render_frame_time.csv
#   $B --benchmark_filter=PhongAccuracy --benchmark_format=csv > docs/plots/render_phong_accuracy.csv
#   $B --benchmark_filter=OrganAccuracy --benchmark_format=csv > docs/plots/render_organ_accuracy.csv
#   gnuplot tools/plots/render.gp        (from the repository root)
# render_frame_time.png: frame time of the visual view against the triangles drawn, one line per
#   input surface size (llvmpipe on the CPU unless the CSV's label says otherwise).
# render_accuracy.png: distance of the tessellated surface from its reference against the
#   tessellation level: a coarse icosphere against the true sphere (relative to the radius), and
#   the bundled organs' coarse boundary against their fine mesh's boundary (mm).
set terminal pngcairo size 1100,420 font ",10"
set datafile separator ","
set grid
set datafile missing NaN
# Google Benchmark's CSV: name is column 1, real_time column 3; counters by header name.
is(s) = (strstrt(strcol(1), s) > 0)
# The one-digit argument after `key` in the benchmark's name ("level:3" -> 3), -1 if absent.
pos(key) = strstrt(strcol(1), key) + strlen(key)
num(key) = (strstrt(strcol(1), key) > 0 ? int(substr(strcol(1), pos(key), pos(key))) : -1)

set output "docs/plots/render_frame_time.png"
set multiplot layout 1,2
set logscale xy
set key top left
set title "Frame time vs triangles drawn (640x480, 4x MSAA, llvmpipe)"
set xlabel "triangles drawn (input x level^2)"
set ylabel "ms per frame (wall)"
plot for [k=0:4] "docs/plots/render_frame_time.csv" \
       using ((is("BM_FrameTime") && num("subdiv:") == k) ? column("drawn_triangles") : NaN):(column("real_time")) \
       with linespoints pt 7 title sprintf("%d input triangles", 20 * 4**k)
unset logscale x
set logscale y
set key top left
set title "Frame time vs tessellation level"
set xlabel "tessellation level"
plot for [k=0:4] "docs/plots/render_frame_time.csv" \
       using ((is("BM_FrameTime") && num("subdiv:") == k) ? num("level:") : NaN):(column("real_time")) \
       with linespoints pt 7 title sprintf("%d input triangles", 20 * 4**k)
unset multiplot

set output "docs/plots/render_accuracy.png"
set multiplot layout 1,2
unset logscale
set logscale y
set key top right
set title "Icosphere (radius 1, radial normals) vs the true sphere"
set xlabel "tessellation level (1 = flat)"
set ylabel "max distance / radius"
plot for [k=0:2] "docs/plots/render_phong_accuracy.csv" \
       using ((is("BM_PhongAccuracy") && num("subdiv:") == k) ? num("level:") : NaN):(column("max_dist_rel")) \
       with linespoints pt 7 title sprintf("%d input triangles, max", 20 * 4**k), \
     for [k=0:2] "" \
       using ((is("BM_PhongAccuracy") && num("subdiv:") == k) ? num("level:") : NaN):(column("mean_dist_rel")) \
       with linespoints dt 2 pt 6 title sprintf("%d input triangles, mean", 20 * 4**k)
unset logscale
set key top left
set title "Coarse organ boundary (Phong, area-weighted normals) vs fine mesh"
set ylabel "distance to the fine boundary (mm)"
set yrange [0:*]
plot "docs/plots/render_organ_accuracy.csv" \
       using ((is("BM_OrganAccuracy") && num("organ:") == 0) ? num("level:") : NaN):(column("max_dist_mm")) \
       with linespoints pt 7 title "liver, max", \
     "" using ((is("BM_OrganAccuracy") && num("organ:") == 0) ? num("level:") : NaN):(column("mean_dist_mm")) \
       with linespoints dt 2 pt 6 title "liver, mean", \
     "" using ((is("BM_OrganAccuracy") && num("organ:") == 1) ? num("level:") : NaN):(column("max_dist_mm")) \
       with linespoints pt 5 title "appendectomy, max", \
     "" using ((is("BM_OrganAccuracy") && num("organ:") == 1) ? num("level:") : NaN):(column("mean_dist_mm")) \
       with linespoints dt 2 pt 4 title "appendectomy, mean"
unset multiplot
