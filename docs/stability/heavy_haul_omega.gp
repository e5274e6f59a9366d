set terminal pngcairo size 1000,700 font ',10'
set output 'heavy_haul_omega.png'
set datafile separator ','
set multiplot layout 2,1 title 'Heavy haul y = 14.85 mm, fz = 100 kN, wheelset angular velocity (paper Fig. 14)'
set grid
set key outside right
set xlabel 'omega, rad/s'
set ylabel 'F_y / F_z (L/V), -'
plot 'heavy_haul_omega.csv' using ($1==0 ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title 'planar', 'heavy_haul_omega.csv' using ($1==1 ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title 'planar-icp', 'heavy_haul_omega.csv' using ($1==2 ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title 'curved'
set ylabel 'contact location y_r of the resultant, mm'
plot 'heavy_haul_omega.csv' using ($1==0 ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title 'planar', 'heavy_haul_omega.csv' using ($1==1 ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title 'planar-icp', 'heavy_haul_omega.csv' using ($1==2 ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title 'curved'
unset multiplot
