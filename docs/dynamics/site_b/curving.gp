set terminal pngcairo size 1000,800 font ',10'
set output 'curving.png'
set datafile separator ','
set grid
set key outside right
set logscale x
set xrange [300:6000]
set xlabel 'curve radius, m'
set multiplot layout 2,1 title 'The bogie in steady curves at 100 mm cant deficiency (site_b_vehicle.h5): table (dots) and solver (circles)' noenhanced
set ylabel 'Y/Q'
plot 'curving.csv' skip 1 using (strcol(14) eq 'leading outer' && strcol(3) eq 'table' ? $1 : 1/0):17 with points lc 1 pt 7 ps 1.2 title 'leading outer', '' skip 1 using (strcol(14) eq 'leading outer' && strcol(3) eq 'solver' ? $1 : 1/0):17 with points lc 1 pt 6 ps 2 notitle, 'curving.csv' skip 1 using (strcol(14) eq 'leading inner' && strcol(3) eq 'table' ? $1 : 1/0):17 with points lc 2 pt 7 ps 1.2 title 'leading inner', '' skip 1 using (strcol(14) eq 'leading inner' && strcol(3) eq 'solver' ? $1 : 1/0):17 with points lc 2 pt 6 ps 2 notitle, 'curving.csv' skip 1 using (strcol(14) eq 'trailing outer' && strcol(3) eq 'table' ? $1 : 1/0):17 with points lc 3 pt 7 ps 1.2 title 'trailing outer', '' skip 1 using (strcol(14) eq 'trailing outer' && strcol(3) eq 'solver' ? $1 : 1/0):17 with points lc 3 pt 6 ps 2 notitle, 'curving.csv' skip 1 using (strcol(14) eq 'trailing inner' && strcol(3) eq 'table' ? $1 : 1/0):17 with points lc 4 pt 7 ps 1.2 title 'trailing inner', '' skip 1 using (strcol(14) eq 'trailing inner' && strcol(3) eq 'solver' ? $1 : 1/0):17 with points lc 4 pt 6 ps 2 notitle
set ylabel 'T{/Symbol g}, N'
plot 'curving.csv' skip 1 using (strcol(14) eq 'leading outer' && strcol(3) eq 'table' ? $1 : 1/0):18 with points lc 1 pt 7 ps 1.2 title 'leading outer', '' skip 1 using (strcol(14) eq 'leading outer' && strcol(3) eq 'solver' ? $1 : 1/0):18 with points lc 1 pt 6 ps 2 notitle, 'curving.csv' skip 1 using (strcol(14) eq 'leading inner' && strcol(3) eq 'table' ? $1 : 1/0):18 with points lc 2 pt 7 ps 1.2 title 'leading inner', '' skip 1 using (strcol(14) eq 'leading inner' && strcol(3) eq 'solver' ? $1 : 1/0):18 with points lc 2 pt 6 ps 2 notitle, 'curving.csv' skip 1 using (strcol(14) eq 'trailing outer' && strcol(3) eq 'table' ? $1 : 1/0):18 with points lc 3 pt 7 ps 1.2 title 'trailing outer', '' skip 1 using (strcol(14) eq 'trailing outer' && strcol(3) eq 'solver' ? $1 : 1/0):18 with points lc 3 pt 6 ps 2 notitle, 'curving.csv' skip 1 using (strcol(14) eq 'trailing inner' && strcol(3) eq 'table' ? $1 : 1/0):18 with points lc 4 pt 7 ps 1.2 title 'trailing inner', '' skip 1 using (strcol(14) eq 'trailing inner' && strcol(3) eq 'solver' ? $1 : 1/0):18 with points lc 4 pt 6 ps 2 notitle
unset multiplot
