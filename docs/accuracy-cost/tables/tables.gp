set terminal pngcairo noenhanced size 1400,620 font ',10'
set output 'tables.png'
set multiplot layout 1,2 title "mbench.toml: verified p95 force error against generation cost (1000 exact solves per table)"
set logscale xy
set grid
set key top right
set yrange [0.1:*]
set ylabel 'p95 force error, % of the local wheel load'
set xlabel 'generation CPU time (s, all threads)'
plot 'tables_refined.dat' using 1:4 with linespoints pt 7 lc rgb '#2166ac' title 'refined (quantile stop), multilinear', 'tables_refined.dat' using 1:5 with linespoints pt 6 lc rgb '#67a9cf' title 'refined (quantile stop), cubic', 'tables_midpoint_rule.dat' using 1:4 with linespoints pt 7 lc rgb '#b2182b' title 'midpoint rule, its passes, multilinear', 'tables_midpoint_rule.dat' using 1:5 with linespoints pt 6 lc rgb '#ef8a62' title 'midpoint rule, its passes, cubic', 1 with lines dt 2 lc rgb '#404040' title '1 % of the load'
set xlabel 'table file (MB)'
plot 'tables_refined.dat' using 2:4 with linespoints pt 7 lc rgb '#2166ac' title 'refined (quantile stop), multilinear', 'tables_refined.dat' using 2:5 with linespoints pt 6 lc rgb '#67a9cf' title 'refined (quantile stop), cubic', 'tables_midpoint_rule.dat' using 2:4 with linespoints pt 7 lc rgb '#b2182b' title 'midpoint rule, its passes, multilinear', 'tables_midpoint_rule.dat' using 2:5 with linespoints pt 6 lc rgb '#ef8a62' title 'midpoint rule, its passes, cubic', 1 with lines dt 2 lc rgb '#404040' title '1 % of the load'
unset multiplot
