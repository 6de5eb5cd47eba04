#!/usr/bin/perl
# Writes signals.xls for tests/app/test_lab_data.cpp: the clean synthetic Kolsky record of that
# test (1 MHz, 800 samples) on a sheet "signals" after a sheet "notes", as an Excel 97 (BIFF8)
# workbook. Needs Debian's libspreadsheet-writeexcel-perl; run: perl make_signals_xls.pl
use strict;
use warnings;
use Spreadsheet::WriteExcel;

sub trap {
  my ($t, $t0, $length, $rise) = @_;
  my $u = $t - $t0;
  return 0.0 if $u <= 0 || $u >= $length;
  return $u / $rise if $u < $rise;
  return ($length - $u) / $rise if $u > $length - $rise;
  return 1.0;
}

my $book = Spreadsheet::WriteExcel->new('signals.xls') or die "signals.xls: $!";
my $notes = $book->add_worksheet('notes');
$notes->write(0, 0, 'synthetic record: incident -1e-3 at 50 us, reflected +0.6e-3 at 450 us, transmitted -0.4e-3 at 350 us');
my $sheet = $book->add_worksheet('signals');
$sheet->write(0, 0, 'time_s');
$sheet->write(0, 1, 'incident');
$sheet->write(0, 2, 'transmitted');
for my $i (0 .. 799) {
  my $t = $i * 1e-6;
  $sheet->write_number($i + 1, 0, $t);
  $sheet->write_number($i + 1, 1, -1e-3 * trap($t, 50e-6, 100e-6, 10e-6) + 0.6e-3 * trap($t, 450e-6, 100e-6, 10e-6));
  $sheet->write_number($i + 1, 2, -0.4e-3 * trap($t, 350e-6, 100e-6, 10e-6));
}
$book->close();
