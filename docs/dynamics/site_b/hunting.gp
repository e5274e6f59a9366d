set terminal pngcairo size 1000,700 font ',10'
set output 'hunting.png'
set datafile separator ','
set grid
set key left top
set multiplot layout 2,1 title 'Hunting against speed (site_b_vehicle.h5)' noenhanced
set xlabel 'V, m/s'
set ylabel 'growth rate, 1/s'
plot 'speeds.csv' using (strcol(1) eq 'table' ? $2 : 1/0):4 with linespoints pt 7 title 'table', '' using (strcol(1) eq 'solver' ? $2 : 1/0):4 with points pt 5 ps 1.5 title 'solver', 0 notitle lc 'black'
set ylabel 'frequency, Hz'
plot 'speeds.csv' using (strcol(1) eq 'table' ? $2 : 1/0):3 with linespoints pt 7 title 'table', '' using (strcol(1) eq 'solver' ? $2 : 1/0):3 with points pt 5 ps 1.5 title 'solver'
unset multiplot
