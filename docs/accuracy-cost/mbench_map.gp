set terminal pngcairo noenhanced size 1000,760 font ',10'
set output '/tmp/vmap/mbench_map.png'
set title "mbench.h5: error of fy (table − solver, % of the local wheel load)\nthrough fz = 6116.32, roll = -0.00190526, spin = -0.00925887; lines: table nodes"
set xlabel 'y_wheel (mm)'
set ylabel 'yaw (rad)'
set cblabel 'fy error (% of load)'
set palette defined (-1 '#2166ac', 0 '#f7f7f7', 1 '#b2182b')
stats '/tmp/vmap/mbench_map.dat' using 3 nooutput
m = (abs(STATS_min) > abs(STATS_max) ? abs(STATS_min) : abs(STATS_max))
if (m <= 0) m = 1
set cbrange [-m:m]
set xrange [-10.92:10.92]
set yrange [-0.01:0.01]
plot '/tmp/vmap/mbench_map.dat' using 1:2:3 with image notitle, '/tmp/vmap/mbench_map.nodes' using 1:2:3:4 with vectors nohead lc rgb '#60000000' lw 0.5 notitle
