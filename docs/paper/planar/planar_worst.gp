set terminal pngcairo size 1300,480 font ',10'
set output 'planar_worst.png'
set multiplot layout 1,3 title 'whl\_left\_iter288 on avg\_low2, y = 3 mm, yaw = 0 rad: the case with the largest L/V difference (paper Fig. 19)'
set xlabel 'lateral position y, track frame, mm'
set ylabel 'line load, N/mm'
set grid
set key top left
set title 'curved reference'
plot 'planar_worst.dat' using ($1==0 ? $2 : 1/0):3 with lines lw 2 lc rgb 'black' title 'curved', 'planar_worst.dat' using ($1==1 ? $2 : 1/0):3 with lines title 'crv-icp'
set title 'weighted centre'
plot 'planar_worst.dat' using ($1==0 ? $2 : 1/0):3 with lines lw 2 lc rgb 'black' title 'curved', 'planar_worst.dat' using ($1==2 ? $2 : 1/0):3 with lines title 'wgt-loc-1', 'planar_worst.dat' using ($1==3 ? $2 : 1/0):3 with lines title 'wgt-loc-2', 'planar_worst.dat' using ($1==4 ? $2 : 1/0):3 with lines title 'wgt-wgt-1', 'planar_worst.dat' using ($1==5 ? $2 : 1/0):3 with lines title 'wgt-wgt-2'
set title 'initial contact'
plot 'planar_worst.dat' using ($1==0 ? $2 : 1/0):3 with lines lw 2 lc rgb 'black' title 'curved', 'planar_worst.dat' using ($1==6 ? $2 : 1/0):3 with lines title 'icp-loc', 'planar_worst.dat' using ($1==7 ? $2 : 1/0):3 with lines title 'icp-wgt-1', 'planar_worst.dat' using ($1==8 ? $2 : 1/0):3 with lines title 'icp-wgt-2'
unset multiplot
