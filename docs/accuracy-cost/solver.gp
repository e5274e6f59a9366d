set terminal pngcairo noenhanced size 1000,650 font ',10'
set output 'solver.png'
set logscale xy
set format xy '%g'
set grid
set key outside right top box opaque Left reverse width 1
set xlabel 'time per solve, s'
set ylabel 'error of fy against 0.1 mm elements, fraction of fz'
set title 'Solver accuracy against cost (point labels: element size dx = ds, mm)'
set offsets graph 0.05, graph 0.1, graph 0.05, graph 0.05
plot 'solver_lines.dat' index 0 using 2:3 with linespoints lw 2 pt 7 lc rgb '#1b9e77' title 'mbench_y0.toml', '' index 0 using 2:3:(sprintf('%g', $1)) with labels offset char 1.2,0.6 tc rgb '#1b9e77' notitle, 'solver_lines.dat' index 1 using 2:3 with linespoints lw 2 pt 7 lc rgb '#d95f02' title 'mbench_y2.toml', '' index 1 using 2:3:(sprintf('%g', $1)) with labels offset char 1.2,0.6 tc rgb '#d95f02' notitle, 'solver_lines.dat' index 2 using 2:3 with linespoints lw 2 pt 7 lc rgb '#7570b3' title 'mbench_y4.toml', '' index 2 using 2:3:(sprintf('%g', $1)) with labels offset char 1.2,0.6 tc rgb '#7570b3' notitle, 'solver_lines.dat' index 3 using 2:3 with linespoints lw 2 pt 7 lc rgb '#e7298a' title 'mbench_y6.toml', '' index 3 using 2:3:(sprintf('%g', $1)) with labels offset char 1.2,0.6 tc rgb '#e7298a' notitle, 'solver_lines.dat' index 4 using 2:3 with linespoints lw 2 pt 7 lc rgb '#66a61e' title 'mbench_y8.toml', '' index 4 using 2:3:(sprintf('%g', $1)) with labels offset char 1.2,0.6 tc rgb '#66a61e' notitle, 'solver_lines.dat' using 2:($4 > 0 ? $3 : 1/0) with points pt 6 ps 3 lw 2 lc rgb 'black' title "the case file's own element size"
