set terminal pngcairo size 1000,800 font ',10'
set output 'centred.png'
set datafile separator ','
set grid
set key top right
set xlabel 'y, mm'
set multiplot layout 2,1 title 'The wheelset at centred running, 50 m/s (site_b_vehicle.h5)' noenhanced
set ylabel 'F_y, N'
plot 'centred.csv' skip 1 using 1:2 with lines lw 2 title 'table', '' skip 1 using 1:4 with lines title 'solver'
set ylabel 'M_z, N mm'
plot 'centred.csv' skip 1 using 1:3 with lines lw 2 title 'table', '' skip 1 using 1:5 with lines title 'solver'
unset multiplot
