# A CTest entry per shipped scene (inputs/*.ini, label regression): a short run of the scene as it is, and
# one per command of its header comment that selects another rolling law (a line with --contact.rolling=,
# with its continuation lines), so that a renamed key or a too-large dt breaks a test, not a scene.
# Everything comes from the files: the rank count and base options from the header's first "mpirun -n N
# build/rondel inputs/<scene>.ini ...", and a staged scene (its [scene] file = another scene's run output) runs after a
# short run of that scene (a CTest fixture) and reads its output. A new inputs/*.ini needs no CMake edit.

# The header comment (the lines before the first section) of `ini`, continuation lines joined, as a list.
function(_rondel_scene_header ini out)
  file(READ "${ini}" text)
  string(REPLACE ";" "," text "${text}")  # a CMake list would split there
  string(REPLACE "\\" "<bs>" text "${text}")  # a backslash would escape the list separator
  string(REGEX REPLACE "<bs> *\n#" " " text "${text}")  # a continued command is one line
  string(REPLACE "\n" ";" lines "${text}")
  set(result "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^\\[")
      break()
    elseif(line MATCHES "^#(.*)$")
      list(APPEND result "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  set(${out} "${result}" PARENT_SCOPE)
endfunction()

# The value of the first line "key = value" of `ini` ("" when none).
function(_rondel_scene_value ini key out)
  file(STRINGS "${ini}" hits REGEX "^${key} *= *")
  set(first "")
  if(hits)
    list(GET hits 0 first)
    string(REGEX REPLACE "^${key} *= *" "" first "${first}")
  endif()
  set(${out} "${first}" PARENT_SCOPE)
endfunction()

# The --section.key=value options of a documented command, less the output and input directories (the
# test chooses them) and the optional parts in [brackets].
function(_rondel_scene_options line out)
  string(REGEX REPLACE "\\[[^]]*\\]" "" line "${line}")
  string(REGEX MATCHALL "--[a-z_]+\\.[A-Za-z_]+=('[^']*'|[^ ']+)" options "${line}")
  list(FILTER options EXCLUDE REGEX "^--(run\\.output|scene\\.file)=")
  list(TRANSFORM options REPLACE "'" "")  # the shell's quotes
  set(${out} "${options}" PARENT_SCOPE)
endfunction()

# `steps`: the run length ("" for the scene's own run.steps); `setup`/`required`: the fixture this run
# provides/needs (the stage scene it prepares/reads).
function(_rondel_scene_test name scene np args steps setup required)
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/scene-runs/${name}")
  if(required)
    list(APPEND args "--scene.file=${CMAKE_CURRENT_BINARY_DIR}/scene-runs/${required}")
  endif()
  string(REPLACE ";" "|" args "${args}")  # a CMake list would split the argument
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} -D RONDEL=$<TARGET_FILE:rondel> -D MPIEXEC=${MPIEXEC_EXECUTABLE} -D NP=${np}
                   -D SCENE=${scene} -D OUT_DIR=${out_dir} -D SOURCE_DIR=${CMAKE_SOURCE_DIR} -D STEPS=${steps}
                   "-DARGS=${args}" -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/RunScene.cmake)
  if(steps)
    set_tests_properties(${name} PROPERTIES LABELS regression TIMEOUT 300)
  else()
    set_tests_properties(${name} PROPERTIES LABELS "regression;long" TIMEOUT 3600)
  endif()
  if(setup)
    set_tests_properties(${name} PROPERTIES FIXTURES_SETUP ${name})
  endif()
  if(required)
    set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED ${required})
  endif()
endfunction()

function(rondel_add_scene_tests)
  set(RONDEL_SCENE_STEPS 200)
  file(GLOB scenes CONFIGURE_DEPENDS RELATIVE ${CMAKE_SOURCE_DIR} ${CMAKE_SOURCE_DIR}/inputs/*.ini)
  # Which scene writes which output directory (for the staged scenes).
  foreach(scene IN LISTS scenes)
    get_filename_component(stem ${scene} NAME_WE)
    _rondel_scene_value(${CMAKE_SOURCE_DIR}/${scene} output out)
    set(writer_of_${out} ${stem})
    set(used_${stem} FALSE)
  endforeach()
  foreach(scene IN LISTS scenes)
    get_filename_component(stem ${scene} NAME_WE)
    _rondel_scene_value(${CMAKE_SOURCE_DIR}/${scene} file input)
    if(input AND DEFINED writer_of_${input})
      set(needs_${stem} ${writer_of_${input}})
      set(used_${writer_of_${input}} TRUE)
    endif()
  endforeach()
  foreach(scene IN LISTS scenes)
    get_filename_component(stem ${scene} NAME_WE)
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/${scene})
    _rondel_scene_header(${CMAKE_SOURCE_DIR}/${scene} header)
    # The first command of the header that runs this scene gives the rank count and the base options
    # (e.g. biaxial_jiang needs jiang.delta on the command line); without one, the scene as it is.
    string(REPLACE "." "\\." escaped "${scene}")
    set(np 1)
    set(first "")
    foreach(line IN LISTS header)
      if(line MATCHES "mpirun -n ([0-9]+) build/rondel ${escaped}")
        set(np ${CMAKE_MATCH_1})
        set(first "${line}")
        break()
      endif()
    endforeach()
    _rondel_scene_options("${first}" options)
    set(needs "")
    if(needs_${stem})
      set(needs inputs.${needs_${stem}})
    endif()
    _rondel_scene_test(inputs.${stem} ${scene} ${np} "${options}" ${RONDEL_SCENE_STEPS} "${used_${stem}}" "${needs}")
    # The whole run as shipped (label long; the short run above is its CI variant).
    if(needs)
      set(needs ${needs}.full)
    endif()
    _rondel_scene_test(inputs.${stem}.full ${scene} ${np} "${options}" "" "${used_${stem}}" "${needs}")
    # The other documented commands that select a rolling law.
    foreach(line IN LISTS header)
      if(line STREQUAL first OR NOT line MATCHES "--contact\\.rolling=([a-z_]+)")
        continue()
      endif()
      set(law ${CMAKE_MATCH_1})
      if(line MATCHES "inputs/" AND NOT line MATCHES "${escaped}")
        continue()  # a command of another scene
      endif()
      _rondel_scene_options("${line}" options)
      set(name inputs.${stem}.${law})
      set(k 2)
      while(TEST ${name})
        set(name inputs.${stem}.${law}.${k})
        math(EXPR k "${k} + 1")
      endwhile()
      set(needs "")
      if(needs_${stem})
        set(needs inputs.${needs_${stem}})
      endif()
      _rondel_scene_test(${name} ${scene} ${np} "${options}" ${RONDEL_SCENE_STEPS} FALSE "${needs}")
    endforeach()
  endforeach()
endfunction()
