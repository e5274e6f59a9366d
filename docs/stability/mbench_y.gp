set terminal pngcairo size 1000,700 font ',10'
set output 'mbench_y.png'
set datafile separator ','
set multiplot layout 2,1 title 'Manchester S1002/UIC60, lateral shift, fz = 10 kN'
set grid
set key outside right
set xlabel 'wheelset y, mm'
set ylabel 'F_y / F_z (L/V), -'
plot 'mbench_y.csv' using ($1==0 ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title 'planar', 'mbench_y.csv' using ($1==1 ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title 'planar-icp', 'mbench_y.csv' using ($1==2 ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title 'curved'
set ylabel 'contact location y_r of the resultant, mm'
plot 'mbench_y.csv' using ($1==0 ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title 'planar', 'mbench_y.csv' using ($1==1 ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title 'planar-icp', 'mbench_y.csv' using ($1==2 ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title 'curved'
unset multiplot
