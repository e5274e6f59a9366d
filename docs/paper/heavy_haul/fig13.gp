set terminal pngcairo size 1200,850 font ',10'
set output 'fig13.png'
set datafile separator ','
set grid
set key top left
set multiplot layout 2,2 title 'Heavy haul, y = 14.85 mm: two patches merge (paper Fig. 13); bottom: around the jump, step halved'
set xlabel 'wheelset z, mm'
set ylabel 'F_z, kN'
set key top left
set xrange [*:*]
plot 'fig13.csv' skip 1 using ($1==0 ? $4 : 1/0):($8/1000) with linespoints lc rgb '#d62728' pt 7 ps 0.4 title 'icp-loc', 'fig13.csv' skip 1 using ($1==1 ? $4 : 1/0):($8/1000) with linespoints lc rgb '#1f77b4' pt 7 ps 0.4 title 'curved'
set ylabel 'L/V = F_y / F_z, -'
set key bottom left
set xrange [*:*]
plot 'fig13.csv' skip 1 using ($1==0 ? $4 : 1/0):9 with linespoints lc rgb '#d62728' pt 7 ps 0.4 title 'icp-loc', 'fig13.csv' skip 1 using ($1==1 ? $4 : 1/0):9 with linespoints lc rgb '#1f77b4' pt 7 ps 0.4 title 'curved'
set ylabel 'F_z, kN'
set key top left
set xrange [1.175:1.2]
plot 'fig13.csv' skip 1 using ($1==0 ? $4 : 1/0):($8/1000) with linespoints lc rgb '#d62728' pt 7 ps 0.4 title 'icp-loc', 'fig13.csv' skip 1 using ($1==1 ? $4 : 1/0):($8/1000) with linespoints lc rgb '#1f77b4' pt 7 ps 0.4 title 'curved'
set ylabel 'L/V = F_y / F_z, -'
set key bottom left
set xrange [1.175:1.2]
plot 'fig13.csv' skip 1 using ($1==0 ? $4 : 1/0):9 with linespoints lc rgb '#d62728' pt 7 ps 0.4 title 'icp-loc', 'fig13.csv' skip 1 using ($1==1 ? $4 : 1/0):9 with linespoints lc rgb '#1f77b4' pt 7 ps 0.4 title 'curved'
unset multiplot
