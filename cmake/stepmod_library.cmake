# stepmod_library(<name> <source>...): the static library of one layer folder. Its headers are
# included as "<folder>/<file>.hpp" from the repository root (a PUBLIC include directory, so that
# what links it needs nothing more), and it uses threads (std::thread, atomics waits).
function(stepmod_library name)
  add_library(${name} STATIC ${ARGN})
  target_include_directories(${name} PUBLIC ${CMAKE_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC Threads::Threads)
endfunction()
