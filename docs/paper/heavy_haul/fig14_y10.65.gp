set terminal pngcairo size 1200,500 font ',10'
set output 'fig14_y10.65.png'
set datafile separator ','
set grid
set key bottom right
set multiplot layout 1,2 title 'Heavy haul, high-mileage wheel, y = 10.65 mm, F_z = 160 kN: creep forces against the angular velocity (paper Fig. 14)'
set xlabel 'omega, rad/s'
set ylabel 'F_x, kN'
plot 'fig14_y10.65.csv' skip 1 using ($1==0 ? $3 : 1/0):($5/1000) with linespoints lc rgb '#d62728' pt 7 ps 0.4 title 'icp-loc', 'fig14_y10.65.csv' skip 1 using ($1==1 ? $3 : 1/0):($5/1000) with linespoints lc rgb '#2ca02c' pt 7 ps 0.4 title 'wgt-loc-2', 'fig14_y10.65.csv' skip 1 using ($1==2 ? $3 : 1/0):($5/1000) with linespoints lc rgb '#1f77b4' pt 7 ps 0.4 title 'curved'
set ylabel 'F_s (sum over patches), kN'
plot 'fig14_y10.65.csv' skip 1 using ($1==0 ? $3 : 1/0):($6/1000) with linespoints lc rgb '#d62728' pt 7 ps 0.4 title 'icp-loc', 'fig14_y10.65.csv' skip 1 using ($1==1 ? $3 : 1/0):($6/1000) with linespoints lc rgb '#2ca02c' pt 7 ps 0.4 title 'wgt-loc-2', 'fig14_y10.65.csv' skip 1 using ($1==2 ? $3 : 1/0):($6/1000) with linespoints lc rgb '#1f77b4' pt 7 ps 0.4 title 'curved'
unset multiplot
