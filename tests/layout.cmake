# The layout of the source tree (tests/layout/circles.py): each file's
# includes of other rooms against its target's target_link_libraries, and
# no circle of files inside a room (file A depends on file B when A's object
# uses a name B's object defines; `nm` on the build tree's objects, so it
# runs after the build).  It prints the layout summary: rooms, files over
# 800 lines, circles and the allowed ones still left.
find_package(Python3 REQUIRED COMPONENTS Interpreter)
add_test(NAME test_layout_circles
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/layout/circles.py
          ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR})
set_tests_properties(test_layout_circles PROPERTIES TIMEOUT 120 LABELS "layout;quick")
