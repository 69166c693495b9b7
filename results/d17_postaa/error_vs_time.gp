set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set xlabel 'core-ns per pixel (median, one thread)'
set ylabel 'RMS error on edge pixels'
set grid
set key outside right top
set logscale x
set offsets graph 0.1, graph 0.1, graph 0.1, graph 0.1
plot 'error_vs_time.csv' every ::0::0 using 2:3 with points pt 5 lc 1 ps 2 title 'pinwheel 4 bilinear', 'error_vs_time.csv' every ::1::1 using 2:3 with points pt 6 lc 2 ps 2 title 'diagonal 4 bilinear', 'error_vs_time.csv' every ::2::2 using 2:3 with points pt 7 lc 3 ps 2 title 'direct 8 point', 'error_vs_time.csv' every ::3::3 using 2:3 with points pt 8 lc 4 ps 2 title 'supersampling 2x2', 'error_vs_time.csv' every ::4::4 using 2:3 with points pt 9 lc 5 ps 2 title 'supersampling 4x4'
