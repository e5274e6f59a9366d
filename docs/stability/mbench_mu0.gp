set terminal pngcairo size 1000,700 font ',10'
set output 'mbench_mu0.png'
set datafile separator ','
set multiplot layout 2,1 title 'Manchester, frictionless (mu = 0)'
set grid
set key outside right
set xlabel 'wheelset y, mm'
set ylabel 'F_y / F_z (L/V), -'
plot 'mbench_mu0.csv' using ($1==0 ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title 'planar', 'mbench_mu0.csv' using ($1==1 ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title 'planar-icp', 'mbench_mu0.csv' using ($1==2 ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title 'curved'
set ylabel 'contact location y_r of the resultant, mm'
plot 'mbench_mu0.csv' using ($1==0 ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title 'planar', 'mbench_mu0.csv' using ($1==1 ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title 'planar-icp', 'mbench_mu0.csv' using ($1==2 ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title 'curved'
unset multiplot
