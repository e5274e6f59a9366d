set terminal pngcairo size 900,600 font ',10'
set output 'solver.png'
set datafile separator ','
set logscale xy
set grid
set xlabel 'time per solve, s'
set ylabel 'error of fy against dx = 0.1 mm, fraction of fz'
set title 'Solver accuracy against cost: Manchester S1002/UIC60, curved, fz = 10 kN'
plot 'solver.csv' using 3:($9>0?$9:1/0):(sprintf('%.2g', $1)) with labels offset 1,0.5 notitle, '' using 3:($9>0?$9:1/0) with points pt 7 title 'one case (label: element size, mm)'
