# Digitised figures (WebPlotDigitizer x,y exports) and the observation reader.

# A two-column export given where an observation CSV belongs: the error names the file and the
# options that read it, and nothing is fitted. (`.` stands for the message's ';', which CMake
# would take for a list separator.)
sedwave_cli_case(digitized.two_column_export_in_observation_reader 1
  "figure_export.csv: this looks like a two-column digitised export. read it with --digitized-file [^ ]*figure_export.csv --digitized QUANTITY:FREQ_UNIT:VALUE_UNIT"
  invert ${CLI_DATA}/digitized/figure_export.csv --no-plot --out ${CLI_OUT}/digitized_as_observations)

# The same file read the way the message says: a converged fit of attenuation alone with d fixed.
sedwave_cli_case(digitized.export_read_with_digitized_option 3
  "report: .*fit.json"
  invert --digitized-file ${CLI_DATA}/digitized/figure_export.csv --digitized attenuation:kHz:dB/m:0.1
  --model continuum --fit kappa,gamma --d 3e-4 --method ceres --no-plot --out ${CLI_OUT}/digitized_read)

# data/field holds observation CSVs only (digitised exports live in data/digitized), so
# `sedwave invert data/field/*.csv` reads every file there.
file(GLOB field_observation_files ${PROJECT_SOURCE_DIR}/data/field/*.csv)
sedwave_cli_case(digitized.field_directory_reads_as_observations 3
  "[0-9]+ observations"
  invert ${field_observation_files} --method ceres --no-plot --out ${CLI_OUT}/digitized_field)
