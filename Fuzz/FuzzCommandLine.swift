// libFuzzer harness for the command line: the ArgumentParser stand-in and
// the validation of `raytrace`'s commands. Built and run by Fuzz/run.sh,
// not by SwiftPM.
//
// The input is split into arguments at NUL bytes (as the kernel hands them
// to a process; invalid UTF-8 is repaired as `CommandLine.arguments`
// repairs it) and parsed as `raytrace ARGUMENTS` is, by
// `Raytrace.parseCommand(_:)` (the `render` command when no other is named).
// Parsing includes each command's `validate()`; `run()` is never called, so
// nothing is rendered, read or written. (An earlier version also parsed
// every input as the `render` command at the root, which the program never
// does; it halved the rate for no code the program runs.)
//
// Checked: no trap; an error has a non-empty message and exits with 0 (help)
// or 64 (usage), since parsing and validation throw nothing else; the help
// and error texts are built, as `raytrace` would print them.

import ArgumentParser
@testable import raytrace

@_cdecl("LLVMFuzzerTestOneInput")
public func fuzzCommandLine(_ data: UnsafePointer<UInt8>?, _ size: Int) -> CInt
{
  let bytes = data.map { UnsafeBufferPointer(start: $0, count: size) }
  let arguments =
    bytes.map { bytes in
      bytes.split(separator: 0, omittingEmptySubsequences: false).map {
        String(decoding: $0, as: UTF8.self)
      }
    } ?? []
  check(Raytrace.self, arguments) { try Raytrace.parseCommand(arguments) }
  return 0
}

/// Parses with `parse` and builds what `exit(withError:)` would print.
func check<Command: ParsableCommand>(
  _ command: Command.Type, _ arguments: [String], _ parse: () throws -> Any
) {
  do {
    _ = try parse()
  } catch {
    let code = Command.exitCode(for: error).rawValue
    guard code == 0 || code == 64 else {
      fatalError("fuzz invariant: exit code \(code) for \(arguments): \(error)")
    }
    let text = Command.fullMessage(for: error, columns: 80)
    guard !text.isEmpty else {
      fatalError("fuzz invariant: no message for \(arguments): \(error)")
    }
  }
}
