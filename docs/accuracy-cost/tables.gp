set terminal pngcairo noenhanced size 1000,650 font ',10'
set output 'tables.png'
set logscale xy
set grid
set key top right
set offsets graph 0.1, graph 0.1, 0, 0
set xlabel 'table points'
set ylabel 'p95 force error, % of the local wheel load'
set yrange [0.1:*]
set title "mbench.toml: interpolation error against table size (300 exact solves)"
plot 'tables_uniform.dat' using 1:2 with linespoints pt 5 lc rgb '#b2182b' title 'uniform, multilinear', '' using 1:3 with linespoints pt 4 lc rgb '#ef8a62' title 'uniform, cubic', 'tables_refined.dat' using 1:2 with linespoints pt 7 lc rgb '#2166ac' title 'refined, multilinear', '' using 1:3 with linespoints pt 6 lc rgb '#67a9cf' title 'refined, cubic', 1 with lines dt 2 lc rgb '#404040' title '1 % of the load'
