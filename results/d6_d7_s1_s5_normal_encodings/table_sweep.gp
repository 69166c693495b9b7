set datafile separator comma
set logscale x 2
set logscale y
set xlabel 'table size (texels per side)'
set ylabel 'RMS angular error (deg)'
set grid
set key top right
plot 'table_sweep.csv' skip 1 using (strcol(2) eq '8-bit' && strcol(3) eq 'nearest' ? $1 : 1/0):5 with linespoints title '8-bit, nearest', '' skip 1 using (strcol(2) eq '16-bit' && strcol(3) eq 'nearest' ? $1 : 1/0):5 with linespoints title '16-bit, nearest', '' skip 1 using (strcol(2) eq 'float' && strcol(3) eq 'nearest' ? $1 : 1/0):5 with linespoints title 'float, nearest', '' skip 1 using (strcol(2) eq '16-bit' && strcol(3) eq 'bilinear' ? $1 : 1/0):5 with linespoints title '16-bit, bilinear', 0.036773 with lines dt 2 title 'exact search'
