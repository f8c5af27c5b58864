add_test(NAME "kernels: every kernel compiles as GLSL 330, 450 and ES 3.00" COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/nodes/glsl_kernels_check.sh ${PROJECT_SOURCE_DIR})
