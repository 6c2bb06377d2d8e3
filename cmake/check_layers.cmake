# The layer check (a test: `ctest -R layers`): run as
#   cmake -DSOURCE_DIR=<repo>/src -DLISTED=<file listing the sources of every target> -P this
# Fails when a file includes from a folder above its own, or when a source file in src/ belongs to
# no target. The layers, lowest first (docs/architecture.md):
set(layers core grid physics solver scene cluster surface io whitewater validate raytrace render cli
           python)
# Tests may also use scene/ for their fixtures: a scene file is the shortest honest way to make a
# fluid to test a solver with.
set(fixture_layers scene)

file(READ ${LISTED} listed)
string(REPLACE "\n" ";" listed "${listed}")
file(GLOB_RECURSE files RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/*.h ${SOURCE_DIR}/*.cpp
     ${SOURCE_DIR}/*.cu ${SOURCE_DIR}/*.cuh)
set(problems "")
foreach(file IN LISTS files)
    string(REGEX MATCH "^[^/]+" folder "${file}")
    list(FIND layers ${folder} own)
    if(own LESS 0)
        string(APPEND problems "  ${file}: folder '${folder}' is not a layer (cmake/check_layers.cmake)\n")
        continue()
    endif()
    set(is_test OFF)
    if(file MATCHES "_test(_support)?\\.(cpp|cu|h)$" OR file MATCHES "_test_main\\.cpp$")
        set(is_test ON)
    endif()
    file(STRINGS ${SOURCE_DIR}/${file} includes REGEX "^[ \t]*#[ \t]*include[ \t]+\"[a-z_]+/")
    foreach(line IN LISTS includes)
        string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"([a-z_]+)/.*" "\\1" used "${line}")
        list(FIND layers ${used} theirs)
        if(theirs LESS 0)
            continue()  # not one of weir's folders
        endif()
        if(theirs GREATER own)
            list(FIND fixture_layers ${used} fixture)
            if(NOT (is_test AND fixture GREATER_EQUAL 0))
                string(APPEND problems "  ${file} includes ${used}/, a layer above ${folder}/\n")
            endif()
        endif()
    endforeach()
    if(file MATCHES "\\.(cpp|cu)$")
        list(FIND listed ${SOURCE_DIR}/${file} found)
        if(found LESS 0)
            string(APPEND problems "  ${file} is in no target: list it in src/${folder}/CMakeLists.txt\n")
        endif()
    endif()
endforeach()
if(problems)
    message(FATAL_ERROR "layer check failed:\n${problems}")
endif()
list(LENGTH files count)
message(STATUS "layer check: ${count} files, every include looks down, every source is built")
