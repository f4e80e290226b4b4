
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/apps/picture_options.cpp" "apps/CMakeFiles/runout_pictures.dir/picture_options.cpp.o" "gcc" "apps/CMakeFiles/runout_pictures.dir/picture_options.cpp.o.d"
  "/work/main/apps/render_cli.cpp" "apps/CMakeFiles/runout_pictures.dir/render_cli.cpp.o" "gcc" "apps/CMakeFiles/runout_pictures.dir/render_cli.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/main/build-dev/render/CMakeFiles/runout_render.dir/DependInfo.cmake"
  "/work/main/build-dev/core/CMakeFiles/runout_core.dir/DependInfo.cmake"
  "/work/main/build-dev/core/io/CMakeFiles/runout_io.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
