set terminal pngcairo size 1000,700 font ',10'
set output 'run_127.0ms.png'
set datafile separator ','
set multiplot layout 2,1 title 'Leading wheelset of the bogie at 127.0 m/s (site_b_vehicle.h5): forces from the table and from full solves' noenhanced
set grid
set xlabel 't, s'
set ylabel 'y, mm'
plot 'run_127.0ms.csv' skip 1 using 1:2 with lines lw 2 title 'table', '' skip 1 using 1:4 with lines dt 2 lw 2 title 'solver'
set ylabel 'yaw, mrad'
plot 'run_127.0ms.csv' skip 1 using 1:($3*1000) with lines lw 2 title 'table', '' skip 1 using 1:($5*1000) with lines dt 2 lw 2 title 'solver'
unset multiplot
