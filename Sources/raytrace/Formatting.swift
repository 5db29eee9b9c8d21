import FastEngine
import Pipeline
import Measurement
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// Standard output, written line by line with write(2) so that a failed
/// write is seen (a full device, a closed file): `main` then reports it
/// and exits 1 rather than 0 with the output lost.
enum StandardOutput {
  /// The reason of the first write that failed, if one did.
  nonisolated(unsafe) static var failure: String?

  static func write(_ line: String) {
    if let reason = Platform.writeAll(1, Array((line + "\n").utf8)),
      failure == nil
    {
      failure = reason
    }
  }
}

/// Writes one line to standard output (`StandardOutput`).
func printOutput(_ line: String = "") {
  StandardOutput.write(line)
}

/// Writes one line to standard error.
func printError(_ line: String) {
  // write(2) rather than fputs(stderr): the C global is shared mutable
  // state to Swift 6, and one unbuffered write keeps the line whole.
  _ = Platform.writeAll(2, Array((line + "\n").utf8))
}

func seconds(_ value: Double) -> String {
  formatted(value, digits: 4) + " s"
}

/// `value` with `digits` significant digits, in plain notation.
func formatted(_ value: Double, digits: Int) -> String {
  guard value.isFinite, value != 0 else { return "\(value)" }
  let magnitude = Int(log10(value.magnitude).rounded(.down))
  let decimals = max(0, digits - 1 - magnitude)
  return withFormat("%.\(decimals)f", value)
}

/// `value` as 1.2e-16, or 0.
func scientific(_ value: Double) -> String {
  guard value != 0 else { return "0" }
  guard value.isFinite else { return "\(value)" }
  return withFormat("%.1e", value)
}

private func withFormat(_ format: String, _ value: Double) -> String {
  var buffer = [CChar](repeating: 0, count: 64)
  _ = withVaList([value]) { arguments in
    vsnprintf(&buffer, buffer.count, format, arguments)
  }
  return String(
    decoding: buffer.prefix { $0 != 0 }.map { UInt8(bitPattern: $0) },
    as: UTF8.self)
}

/// The executable's words for a remedy: its own options.
extension Remedy {
  var advice: String {
    switch self {
    case .doublePrecision: "use --precision double"
    case .fastEngine: "use --engine fast"
    }
  }
}

extension SceneError {
  /// The error as the command line reports it: the message, then the
  /// remedy in the command line's own options (for a number beyond the
  /// range it was read for, the remedy that range has).
  var report: String { report(remedy: Remedy(exceeded: exceeded)) }

  /// The message, then `remedy` in the command line's own options.
  func report(remedy: Remedy?) -> String {
    description + (remedy.map { "; " + $0.advice } ?? "")
  }
}
