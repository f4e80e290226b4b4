# Empty dependencies file for runout.
# This may be replaced when dependencies are built.
