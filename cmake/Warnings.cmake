# cbtl_warnings: the warning set for the project's own code. Generated ANTLR code does not use it.
add_library(cbtl_warnings INTERFACE)
target_compile_options(cbtl_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow=local -Wnon-virtual-dtor)
