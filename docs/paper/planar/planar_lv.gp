set terminal pngcairo size 1100,650 font ',10'
set output 'planar_lv.png'
set title 'L/V of every case, sorted by the curved reference (paper Fig. 20)'
set xlabel 'case, by the curved L/V'
set ylabel 'L/V = F_y / F_z, -'
set grid
set key outside right
plot 'planar_lv.dat' using 1:11 with points pt 7 ps 0.5 title 'icp-wgt-2', 'planar_lv.dat' using 1:10 with points pt 7 ps 0.5 title 'icp-wgt-1', 'planar_lv.dat' using 1:9 with points pt 7 ps 0.5 title 'icp-loc', 'planar_lv.dat' using 1:8 with points pt 7 ps 0.5 title 'wgt-wgt-2', 'planar_lv.dat' using 1:7 with points pt 7 ps 0.5 title 'wgt-wgt-1', 'planar_lv.dat' using 1:6 with points pt 7 ps 0.5 title 'wgt-loc-2', 'planar_lv.dat' using 1:5 with points pt 7 ps 0.5 title 'wgt-loc-1', 'planar_lv.dat' using 1:4 with points pt 7 ps 0.5 title 'crv-icp', 'planar_lv.dat' using 1:3 with lines lw 2 lc rgb 'black' title 'curved'
