set terminal pngcairo size 1000,700 font ',10'
set output 'groove_load.png'
set datafile separator ','
set multiplot layout 2,1 title 'Ball R10 in groove R10.02 (nearly conformal), load'
set grid
set key outside right
set logscale x
set xlabel 'fz, N'
set ylabel 'F_y / F_z (L/V), -'
plot 'groove_load.csv' using ($1==0 ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title 'planar', 'groove_load.csv' using ($1==1 ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title 'planar-icp', 'groove_load.csv' using ($1==2 ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title 'curved'
set ylabel 'contact location y_r of the resultant, mm'
plot 'groove_load.csv' using ($1==0 ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title 'planar', 'groove_load.csv' using ($1==1 ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title 'planar-icp', 'groove_load.csv' using ($1==2 ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title 'curved'
unset multiplot
