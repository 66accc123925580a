# Shared compile settings for every uwgrasp target.
function(uwgrasp_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
    -Wcast-align -Woverloaded-virtual)
  if(UWGRASP_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")  # is_finite's & on bools is deliberate (vectorises)
    target_compile_options(${target} PRIVATE -Wno-bitwise-instead-of-logical)
  endif()
  # A fuzz build (UWGRASP_BUILD_FUZZ) instruments only the code that reads outside input (the
  # targets in UWGRASP_INPUT_TARGETS); the rest is plain -O1 code it links against: clang's
  # sanitizer and coverage instrumentation of the template-heavy geometry is 4x slower to compile.
  set(instrument ON)
  if(UWGRASP_BUILD_FUZZ AND NOT target IN_LIST UWGRASP_INPUT_TARGETS)
    set(instrument OFF)
  endif()
  if(UWGRASP_SANITIZE AND instrument)
    target_compile_options(${target} PRIVATE -fsanitize=${UWGRASP_SANITIZE} -fno-omit-frame-pointer
      -fno-sanitize-recover=all)
    target_link_options(${target} PRIVATE -fsanitize=${UWGRASP_SANITIZE})
    # GCC's UBSan null and alignment checks on every pointer access make the geometry (Eigen,
    # inlined deeply) a third slower to compile; where no outside bytes are read, a null pointer
    # still faults under ASan and Eigen's types are aligned by construction.
    if(UWGRASP_SANITIZE_SKIP AND NOT target IN_LIST UWGRASP_INPUT_TARGETS)
      target_compile_options(${target} PRIVATE -fno-sanitize=${UWGRASP_SANITIZE_SKIP})
    endif()
  endif()
  if(UWGRASP_BUILD_FUZZ AND instrument)  # coverage feedback into libFuzzer
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()

# uwgrasp_module(name SOURCES ... DEPS ...): one folder = one static target uwgrasp::name.
function(uwgrasp_module name)
  cmake_parse_arguments(M "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(uwgrasp_${name} STATIC ${M_SOURCES})
  add_library(uwgrasp::${name} ALIAS uwgrasp_${name})
  set_target_properties(uwgrasp_${name} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME uwgrasp_${name})
  target_include_directories(uwgrasp_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(uwgrasp_${name} PUBLIC ${M_PUBLIC_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  target_compile_features(uwgrasp_${name} PUBLIC cxx_std_20)
  uwgrasp_warnings(uwgrasp_${name})
  install(TARGETS uwgrasp_${name} EXPORT uwgraspTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/uwgrasp/${name}
    FILES_MATCHING PATTERN "*.hpp")
endfunction()
