# Web assets (JavaScript, HTML, CSS) compiled into the binary so that the pages masnet serves and
# writes work offline: masnet_embed_assets(TARGET HEADER NAMESPACE FILES...) generates HEADER in
# the build tree with one `inline constexpr std::string_view k<Name>` per file (the file name in
# CamelCase, e.g. scene_view.js -> kSceneViewJs) and adds it to TARGET's include path.
set(MASNET_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/embed_assets_write.cmake)

function(masnet_embed_assets target header namespace)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/embedded/${header})
  # A ';' would split the command line: the script gets the files joined with '|'.
  string(JOIN "|" files ${ARGN})
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DNAMESPACE=${namespace} -DFILES=${files} -P
            ${MASNET_EMBED_SCRIPT}
    DEPENDS ${ARGN} ${MASNET_EMBED_SCRIPT}
    COMMENT "Embedding ${header}"
    VERBATIM)  # quotes the list of FILES, whose ';' a shell would take for a command separator
  target_sources(${target} PRIVATE ${out})
  target_include_directories(${target} PRIVATE ${CMAKE_CURRENT_BINARY_DIR}/embedded)
endfunction()
