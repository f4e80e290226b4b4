file(REMOVE_RECURSE
  "CMakeFiles/runout_io.dir/src/files.cpp.o"
  "CMakeFiles/runout_io.dir/src/files.cpp.o.d"
  "CMakeFiles/runout_io.dir/src/outputs.cpp.o"
  "CMakeFiles/runout_io.dir/src/outputs.cpp.o.d"
  "CMakeFiles/runout_io.dir/src/scene_file.cpp.o"
  "CMakeFiles/runout_io.dir/src/scene_file.cpp.o.d"
  "CMakeFiles/runout_io.dir/src/sweep_file.cpp.o"
  "CMakeFiles/runout_io.dir/src/sweep_file.cpp.o.d"
  "librunout_io.a"
  "librunout_io.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/runout_io.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
