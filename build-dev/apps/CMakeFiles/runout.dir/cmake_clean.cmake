file(REMOVE_RECURSE
  "CMakeFiles/runout.dir/picture_loader.cpp.o"
  "CMakeFiles/runout.dir/picture_loader.cpp.o.d"
  "CMakeFiles/runout.dir/picture_options.cpp.o"
  "CMakeFiles/runout.dir/picture_options.cpp.o.d"
  "CMakeFiles/runout.dir/plot_command.cpp.o"
  "CMakeFiles/runout.dir/plot_command.cpp.o.d"
  "CMakeFiles/runout.dir/prepare.cpp.o"
  "CMakeFiles/runout.dir/prepare.cpp.o.d"
  "CMakeFiles/runout.dir/run_command.cpp.o"
  "CMakeFiles/runout.dir/run_command.cpp.o.d"
  "CMakeFiles/runout.dir/run_folder.cpp.o"
  "CMakeFiles/runout.dir/run_folder.cpp.o.d"
  "CMakeFiles/runout.dir/runout.cpp.o"
  "CMakeFiles/runout.dir/runout.cpp.o.d"
  "CMakeFiles/runout.dir/study_command.cpp.o"
  "CMakeFiles/runout.dir/study_command.cpp.o.d"
  "CMakeFiles/runout.dir/sweep_command.cpp.o"
  "CMakeFiles/runout.dir/sweep_command.cpp.o.d"
  "runout"
  "runout.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/runout.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
