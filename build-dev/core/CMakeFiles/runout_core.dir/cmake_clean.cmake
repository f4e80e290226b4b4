file(REMOVE_RECURSE
  "CMakeFiles/runout_core.dir/src/checkpoint.cpp.o"
  "CMakeFiles/runout_core.dir/src/checkpoint.cpp.o.d"
  "CMakeFiles/runout_core.dir/src/derive.cpp.o"
  "CMakeFiles/runout_core.dir/src/derive.cpp.o.d"
  "CMakeFiles/runout_core.dir/src/measure.cpp.o"
  "CMakeFiles/runout_core.dir/src/measure.cpp.o.d"
  "CMakeFiles/runout_core.dir/src/neighbor_list.cpp.o"
  "CMakeFiles/runout_core.dir/src/neighbor_list.cpp.o.d"
  "CMakeFiles/runout_core.dir/src/run.cpp.o"
  "CMakeFiles/runout_core.dir/src/run.cpp.o.d"
  "CMakeFiles/runout_core.dir/src/setup.cpp.o"
  "CMakeFiles/runout_core.dir/src/setup.cpp.o.d"
  "CMakeFiles/runout_core.dir/src/walls.cpp.o"
  "CMakeFiles/runout_core.dir/src/walls.cpp.o.d"
  "CMakeFiles/runout_core.dir/src/world.cpp.o"
  "CMakeFiles/runout_core.dir/src/world.cpp.o.d"
  "librunout_core.a"
  "librunout_core.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/runout_core.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
