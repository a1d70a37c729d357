# Time per cut (docs/BENCHMARKS.md "Cutting"), from the CSV of one serosa_bench_cutting run:
#   build/<dir>/bench/serosa_bench_cutting --benchmark_filter='BM_CutVs' \
#       --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
#       --benchmark_format=csv > docs/plots/cutting_bench.csv
#   gnuplot tools/plots/cutting.gp        (from the repository root)
# Left: median time per cut (query + cut + apply + BVH update) and its parts against mesh size,
# same blade, and the first cut after loading (a fresh copy with spare capacity, one cut). Right: median time per cut against the tets the blade touches, 100k-tet mesh.
set terminal pngcairo size 1100,420 font ",10"
set output "docs/plots/cutting_time_per_cut.png"
set datafile separator ","
set multiplot layout 1,2
set logscale x
set logscale y
set grid
set key bottom right
# Rows are picked by name (the medians), columns by their header names.
is(s) = (strstrt(strcol(1), s) > 0 && strstrt(strcol(1), "_median") > 0)
set title "Time per cut vs mesh size (same blade, 161 tets touched)"
set xlabel "tets in the mesh"
set ylabel "time per cut (ms)"
set xrange [5e3:2e6]
plot "docs/plots/cutting_bench.csv" using (is("BM_CutVsSize") ? column("tets") : NaN):(column("real_time")/1000) \
       with linespoints lw 2 pt 7 title "total", \
     "" using (is("BM_CutVsSize") ? column("tets") : NaN):(column("cut_us")/1000) with linespoints pt 5 title "cut (incl. BVH query)", \
     "" using (is("BM_CutVsSize") ? column("tets") : NaN):(column("update_us")/1000) with linespoints pt 9 title "TetBvh::update", \
     "" using (is("BM_CutVsSize") ? column("tets") : NaN):(column("apply_us")/1000) with linespoints pt 11 title "apply()", \
     "" using (is("BM_CutVsSize") ? column("tets") : NaN):(column("first_cut_us")/1000) with linespoints dt 2 pt 6 title "first cut after loading (total)"
set title "Time per cut vs tets touched (100k-tet mesh)"
set xlabel "tets touched by the blade"
set xrange [30:1e4]
plot "docs/plots/cutting_bench.csv" using (is("BM_CutVsBlade") ? column("tets_touched") : NaN):(column("real_time")/1000) \
       with linespoints lw 2 pt 7 title "total", \
     "" using (is("BM_CutVsBlade") ? column("tets_touched") : NaN):(column("cut_us")/1000) with linespoints pt 5 title "cut", \
     "" using (is("BM_CutVsBlade") ? column("tets_touched") : NaN):(column("update_us")/1000) with linespoints pt 9 title "TetBvh::update"
unset multiplot
