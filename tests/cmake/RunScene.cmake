# One short run of a shipped scene (CTest entry inputs.*): runs build/rondel on the scene under mpiexec
# from the source root, and fails unless it exits with 0 and writes final.csv.
#   -D RONDEL=... -D MPIEXEC=... -D NP=1 -D SCENE=inputs/x.ini -D OUT_DIR=... -D SOURCE_DIR=...
#   -D STEPS=200 (empty: the scene's own run.steps) -D ARGS="--a=1|--b=2" (the scene's documented overrides, separated by |)
string(REPLACE "|" ";" ARGS "${ARGS}")
file(REMOVE_RECURSE "${OUT_DIR}")
if(STEPS)
  list(APPEND ARGS --run.steps=${STEPS})
endif()
execute_process(COMMAND "${MPIEXEC}" -n ${NP} --oversubscribe --allow-run-as-root "${RONDEL}" "${SCENE}"
                        ${ARGS} "--run.output=${OUT_DIR}" --run.progress=false
                WORKING_DIRECTORY "${SOURCE_DIR}" RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE log)
string(REPLACE ";" " " shown "${ARGS}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "rondel ${SCENE} ${shown} (${NP} ranks) exited with ${rc}:\n${log}")
endif()
if(NOT EXISTS "${OUT_DIR}/final.csv")
  message(FATAL_ERROR "rondel ${SCENE} ${shown} wrote no ${OUT_DIR}/final.csv")
endif()
