set datafile separator comma
set xlabel 'alpha'
set ylabel 'mean angular error (deg)'
set logscale y
set grid
set key outside right
plot for [a in '5 30 90'] 'blending.csv' skip 1 using (strcol(1) eq a ? $2 : 1/0):3 with linespoints title 'best fit, '.a.' deg', for [a in '5 30 90'] '' skip 1 using (strcol(1) eq a ? $2 : 1/0):5 with linespoints dt 2 title 'normalized, '.a.' deg'
