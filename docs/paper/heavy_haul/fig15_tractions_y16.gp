set terminal pngcairo size 1100,840 font ',10'
set output 'fig15_tractions_y16.png'
set datafile separator ','
set multiplot layout 3,2 title 'Tangential tractions at omega = -33.7 rad/s (paper Fig. 15), y = 16 mm'
set xlabel 'lateral position y, track frame, mm'
set ylabel 'x, mm'
set palette defined (-1 '#2166ac', 0 '#f7f7f7', 1 '#b2182b')
set style fill solid
set title 'icp-loc: p_x, N/mm^2'
set cbrange [*:*]
stats 'fig15_16_fields_y16.csv' skip 1 using ($1==0 ? abs($7) : 1/0) nooutput
if (STATS_records > 0) { set cbrange [-STATS_max:STATS_max] }
plot 'fig15_16_fields_y16.csv' skip 1 using ($1==0 ? $11 : 1/0):4:(0.2):(0.2):7 with boxxyerror lc palette notitle
set title 'icp-loc: p_s, N/mm^2'
set cbrange [*:*]
stats 'fig15_16_fields_y16.csv' skip 1 using ($1==0 ? abs($8) : 1/0) nooutput
if (STATS_records > 0) { set cbrange [-STATS_max:STATS_max] }
plot 'fig15_16_fields_y16.csv' skip 1 using ($1==0 ? $11 : 1/0):4:(0.2):(0.2):8 with boxxyerror lc palette notitle
set title 'wgt-loc-2: p_x, N/mm^2'
set cbrange [*:*]
stats 'fig15_16_fields_y16.csv' skip 1 using ($1==1 ? abs($7) : 1/0) nooutput
if (STATS_records > 0) { set cbrange [-STATS_max:STATS_max] }
plot 'fig15_16_fields_y16.csv' skip 1 using ($1==1 ? $11 : 1/0):4:(0.2):(0.2):7 with boxxyerror lc palette notitle
set title 'wgt-loc-2: p_s, N/mm^2'
set cbrange [*:*]
stats 'fig15_16_fields_y16.csv' skip 1 using ($1==1 ? abs($8) : 1/0) nooutput
if (STATS_records > 0) { set cbrange [-STATS_max:STATS_max] }
plot 'fig15_16_fields_y16.csv' skip 1 using ($1==1 ? $11 : 1/0):4:(0.2):(0.2):8 with boxxyerror lc palette notitle
set title 'curved: p_x, N/mm^2'
set cbrange [*:*]
stats 'fig15_16_fields_y16.csv' skip 1 using ($1==2 ? abs($7) : 1/0) nooutput
if (STATS_records > 0) { set cbrange [-STATS_max:STATS_max] }
plot 'fig15_16_fields_y16.csv' skip 1 using ($1==2 ? $11 : 1/0):4:(0.2):(0.2):7 with boxxyerror lc palette notitle
set title 'curved: p_s, N/mm^2'
set cbrange [*:*]
stats 'fig15_16_fields_y16.csv' skip 1 using ($1==2 ? abs($8) : 1/0) nooutput
if (STATS_records > 0) { set cbrange [-STATS_max:STATS_max] }
plot 'fig15_16_fields_y16.csv' skip 1 using ($1==2 ? $11 : 1/0):4:(0.2):(0.2):8 with boxxyerror lc palette notitle
unset multiplot
