extension Platform {
  /// Starts `executable` with `arguments`, its standard output to
  /// /dev/null and its standard error to `errorPipe`: the child's pid, or
  /// the error number `posix_spawn` returned.
  ///
  /// `posix_spawn_file_actions_t` is an opaque pointer on macOS and a
  /// structure on Linux; both are initialised and destroyed here.
  package static func spawn(
    _ executable: String, _ arguments: [String],
    errorPipe: (read: Int32, write: Int32)
  ) -> Result<pid_t, SpawnError> {
    #if canImport(Darwin)
      var actions: posix_spawn_file_actions_t? = nil
    #else
      var actions = posix_spawn_file_actions_t()
    #endif
    posix_spawn_file_actions_init(&actions)
    defer { posix_spawn_file_actions_destroy(&actions) }
    posix_spawn_file_actions_adddup2(&actions, errorPipe.write, 2)
    posix_spawn_file_actions_addclose(&actions, errorPipe.read)
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0)
    let argv = ([executable] + arguments).map { strdup($0) } + [nil]
    defer { argv.forEach { free($0) } }
    var child: pid_t = 0
    let status = posix_spawn(
      &child, executable, &actions, nil, argv, environment)
    guard status == 0 else { return .failure(SpawnError(code: status)) }
    return .success(child)
  }

  package struct SpawnError: Error {
    package var code: Int32
  }
}
