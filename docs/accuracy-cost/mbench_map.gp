set terminal pngcairo noenhanced size 1000,760 font ',10'
set output '/work/main/docs/accuracy-cost/mbench_map.png'
set title "mbench.h5: error of fx (table − solver, % of the local wheel load)\nthrough fz = 18590.9, roll = 0.0017663, spin = -0.00903462; lines: table nodes"
set xlabel 'y_wheel (mm)'
set ylabel 'yaw (rad)'
set cblabel 'fx error (% of load)'
set palette defined (-1 '#2166ac', 0 '#f7f7f7', 1 '#b2182b')
stats '/work/main/docs/accuracy-cost/mbench_map.dat' using 3 nooutput
m = (abs(STATS_min) > abs(STATS_max) ? abs(STATS_min) : abs(STATS_max))
if (m <= 0) m = 1
set cbrange [-m:m]
set xrange [-10.92:10.92]
set yrange [-0.01:0.01]
plot '/work/main/docs/accuracy-cost/mbench_map.dat' using 1:2:3 with image notitle, '/work/main/docs/accuracy-cost/mbench_map.nodes' using 1:2:3:4 with vectors nohead lc rgb '#60000000' lw 0.5 notitle
