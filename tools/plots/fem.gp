# FEM plots of docs/BENCHMARKS.md "FEM", from the CSVs in docs/plots/ (numbers copied from the
# bench/fem runs named in their headers):
#   gnuplot tools/plots/fem.gp        (from the repository root)
# Left: ms per step against tets per solver (CG capped at 20 iterations; CHOLMOD factorizes every
# step). Right: accuracy against time on the 17.5k-tet box: displacement error after 1 s
# relative to the converged (CHOLMOD) run, against ms per step, for CG iteration caps, CG
# tolerances and CG preconditioned by the rest-state CHOLMOD factor.
set terminal pngcairo size 1100,420 font ",10"
set output "docs/plots/fem_step_and_accuracy.png"
set datafile separator ","
set datafile missing "-1"
set multiplot layout 1,2
set logscale xy
set grid
set key top left
set title "ms per step vs mesh size (SOFA box, 2 threads)"
set xlabel "tets"
set ylabel "ms per step"
plot "docs/plots/fem_step_time.csv" using 1:($2 > 0 ? $2 : 1/0) with linespoints title "PCG (Jacobi), 20 it", \
     "" using 1:($3 > 0 ? $3 : 1/0) with linespoints title "PCG matrix-free, 20 it", \
     "" using 1:($4 > 0 ? $4 : 1/0) with linespoints title "PCG + rest CHOLMOD factor, 20 it", \
     "" using 1:($5 > 0 ? $5 : 1/0) with linespoints title "CHOLMOD"
set title "accuracy vs time, 17.5k tets, 100 steps"
set xlabel "ms per step"
set ylabel "displacement error after 1 s (%)"
set key bottom left
fam(s) = strcol(2) eq s
set format y "10^{%L}"
plot "docs/plots/fem_accuracy.csv" using (fam("pcg_cap") ? $3 : 1/0):4 with linespoints title "CG, iteration cap 5..200", \
     "" using (fam("pcg_cap") ? $3 : 1/0):4:1 with labels offset 1.5,0.5 notitle, \
     "" using (fam("pcg_tol") ? $3 : 1/0):4 with linespoints title "CG, tolerance 1e-1..1e-8", \
     "" using (fam("pcg_tol") ? $3 : 1/0):4:1 with labels offset -1.5,-0.7 notitle, \
     "" using (fam("pcg_cholmod") ? $3 : 1/0):4 with linespoints title "CG + rest factor, cap 5, 10"
unset multiplot
