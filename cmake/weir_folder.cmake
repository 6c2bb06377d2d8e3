# One library target per source folder: weir_folder(NAME ...) in src/NAME/CMakeLists.txt makes
# weir_NAME from the folder's sources, linked to the folders below it that it uses (DEPENDS), so
# the layers of docs/architecture.md are what target_link_libraries says. Its tests join the one
# test binary. Every source file in src/ must be listed by its folder: the layer check
# (cmake/check_layers.cmake, a test) fails on a file no folder lists.
#
# weir_folder(NAME
#     SOURCES a.cpp ...         always built
#     CUDA_SOURCES a.cu ...     built when the CUDA backend is
#     TESTS a_test.cpp ...      in weir_tests
#     CUDA_TESTS a_test.cu ...  in weir_tests when the CUDA backend is built
#     DEPENDS weir_x ...        the folders below that it uses (and other libraries), public
#     PRIVATE_DEPENDS ...       libraries used inside only
#     LISTED ...                files of the folder built elsewhere (optional parts), for the check
# )
function(weir_folder name)
    cmake_parse_arguments(F "" ""
                          "SOURCES;CUDA_SOURCES;TESTS;CUDA_TESTS;DEPENDS;PRIVATE_DEPENDS;LISTED"
                          ${ARGN})
    set(sources ${F_SOURCES})
    if(WEIR_HAS_CUDA)
        list(APPEND sources ${F_CUDA_SOURCES})
    endif()
    list(TRANSFORM sources PREPEND ${CMAKE_CURRENT_SOURCE_DIR}/)
    set(target weir_${name})
    if(sources)
        add_library(${target} STATIC ${sources})
        target_link_libraries(${target} PUBLIC weir_options ${F_DEPENDS}
                                        PRIVATE ${F_PRIVATE_DEPENDS})
        target_compile_options(${target} PRIVATE $<$<COMPILE_LANGUAGE:CXX>:${WEIR_WARNINGS}>)
    else()
        add_library(${target} INTERFACE)  # headers only
        target_link_libraries(${target} INTERFACE weir_options ${F_DEPENDS})
    endif()
    set(tests ${F_TESTS})
    if(WEIR_HAS_CUDA)
        list(APPEND tests ${F_CUDA_TESTS})
    endif()
    list(TRANSFORM tests PREPEND ${CMAKE_CURRENT_SOURCE_DIR}/)
    set_property(GLOBAL APPEND PROPERTY WEIR_TEST_SOURCES ${tests})
    set(listed ${F_SOURCES} ${F_CUDA_SOURCES} ${F_TESTS} ${F_CUDA_TESTS} ${F_LISTED})
    foreach(file IN LISTS listed)
        cmake_path(ABSOLUTE_PATH file BASE_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR} NORMALIZE)
        set_property(GLOBAL APPEND PROPERTY WEIR_LISTED_SOURCES ${file})
    endforeach()
endfunction()
