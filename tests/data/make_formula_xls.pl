#!/usr/bin/perl
# Writes formula.xls for tests/core/test_signal_reader.cpp: a sheet "signals" of four samples
# (t, v) whose time cell A3 is the formula =A2+1E-6 with its value stored, as Excel saves it, in an
# Excel 97 (BIFF8) workbook. Needs Debian's libspreadsheet-writeexcel-perl; run: perl
# make_formula_xls.pl
use strict;
use warnings;
use Spreadsheet::WriteExcel;

my $book = Spreadsheet::WriteExcel->new('formula.xls') or die "formula.xls: $!";
my $sheet = $book->add_worksheet('signals');
$sheet->write(0, 0, 't');
$sheet->write(0, 1, 'v');
$sheet->write_number(1, 0, 0);
$sheet->write_formula(2, 0, '=A2+1E-6', undef, 1e-6);
$sheet->write_number(3, 0, 2e-6);
$sheet->write_number(4, 0, 3e-6);
$sheet->write_number($_, 1, $_) for 1 .. 4;
$book->close or die "formula.xls: $!";
