set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set logscale xy
set xlabel 'ns per normal (encode + decode)'
set ylabel 'RMS angular error (deg)'
set grid
set key outside right top font ',8'
set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05
plot 'pareto.csv' every ::0::0 using 2:3 with points pt 1 lc 1 ps 1.5 title 'xyz-normalized', 'pareto.csv' every ::1::1 using 2:3 with points pt 2 lc 2 ps 1.5 title 'xyz-max-component', 'pareto.csv' every ::2::2 using 2:3 with points pt 3 lc 3 ps 1.5 title 'best-fit-search', 'pareto.csv' every ::3::3 using 2:3 with points pt 4 lc 4 ps 1.5 title 'best-fit-search-float', 'pareto.csv' every ::4::4 using 2:3 with points pt 5 lc 5 ps 1.5 title 'octahedral-12', 'pareto.csv' every ::5::5 using 2:3 with points pt 6 lc 6 ps 1.5 title 'octahedral-12-precise', 'pareto.csv' every ::6::6 using 2:3 with points pt 7 lc 7 ps 1.5 title 'spherical-12', 'pareto.csv' every ::7::7 using 2:3 with points pt 8 lc 8 ps 1.5 title 'spherical-z-12', 'pareto.csv' every ::8::8 using 2:3 with points pt 9 lc 1 ps 1.5 title 'mittring-12', 'pareto.csv' every ::9::9 using 2:3 with points pt 10 lc 2 ps 1.5 title 'mittring-8', 'pareto.csv' every ::10::10 using 2:3 with points pt 11 lc 3 ps 1.5 title 'best-fit-table-512-16bit-nearest', 'pareto.csv' every ::11::11 using 2:3 with points pt 12 lc 4 ps 1.5 title 'best-fit-table-512-16bit-bilinear'
