"""The I/O layer: Fortran FORMAT editing and card decks (cards), file reading (inputs), tables as labs write them (table), output directories and files (outputs). It imports nothing above it."""
