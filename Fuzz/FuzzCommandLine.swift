// libFuzzer harness for the command line: the ArgumentParser stand-in and
// the validation of `raytrace`'s commands. Built and run by Fuzz/run.sh,
// not by SwiftPM.
//
// The input is split into arguments at NUL bytes (as the kernel hands them
// to a process; invalid UTF-8 is repaired as `CommandLine.arguments`
// repairs it), parsed as `raytrace ARGUMENTS` and, separately, as the
// `render` command alone. Parsing includes each command's `validate()`;
// `run()` is never called, so nothing is rendered, read or written.
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
  check(Render.self, arguments) { try Render.parse(arguments) }
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
