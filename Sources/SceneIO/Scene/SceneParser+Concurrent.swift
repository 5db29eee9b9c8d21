import Dispatch
import Geometry
import SceneDescription
import PlatformSupport

/// A large group read on two threads: the second starts at a line break
/// near the middle of the file, and its objects are kept only where the
/// sequential parse reaches the same token.
extension SceneParser {
  /// Groups declaring fewer objects are read on one thread.
  static let concurrentGroupSize = 20_000
  /// Nor is a file split where less than this is left to read.
  static let concurrentBytes = 1 << 20

  /// Where a second thread can start reading a large group's objects: the
  /// start of the line nearest the middle of what is left of the file.
  /// Nothing spans a line break (a comment ends there), so the tokens from
  /// there on are the ones the sequential parse reads.
  func speculationPoint(declared: Int) -> Int? {
    let start = tokenizer.position.index
    let bytes = tokenizer.bytes
    guard declared >= concurrentFrom.groupSize,
      bytes.count - start >= concurrentFrom.bytes,
      options.threads > 1
    else { return nil }
    var index = start + (bytes.count - start) / 2
    while index < bytes.count && bytes[index] != UInt8(ascii: "\n") {
      index += 1
    }
    return index + 1 < bytes.count ? index + 1 : nil
  }

  /// Reads the group up to `split` here while another thread reads plain
  /// spheres and material indices from `split` on (see `SphereRun`); when
  /// this thread arrives there at the group's level, it takes the other's
  /// objects and goes on from where the other stopped.
  ///
  /// Whatever the other thread read, the result and every error are the
  /// sequential parse's: the other thread stops before anything it does
  /// not read exactly as this one would (anything but a well-formed
  /// sphere or `MaterialIndex`), and its objects are taken only when this
  /// thread reaches the same token at the group's level with room for
  /// them under `numObjects`; otherwise this thread reads on itself.
  mutating func parseObjectsAlongside(
    _ state: inout GroupState, from split: Int
  ) throws(SceneError) -> GroupProgress {
    var run = SphereRun(
      bytes: tokenizer.source, file: file, options: options, from: split,
      capacity: state.declared.value - state.objects.count)
    run.parser.readsPlainSpheres = readsPlainSpheres
    var outcome: Result<GroupProgress, SceneError> = .success(.spliced)
    withUnsafeMutablePointer(to: &self) { parser in
      withUnsafeMutablePointer(to: &state) { state in
        withUnsafeMutablePointer(to: &run) { run in
          withUnsafeMutablePointer(to: &outcome) { outcome in
            let shared = Shared((parser, state, run, outcome))
            DispatchQueue.concurrentPerform(iterations: 2) { thread in
              let (parser, state, run, outcome) = shared.value
              if thread == 0 {
                do throws(SceneError) {
                  outcome.pointee = .success(
                    try parser.pointee.parseObjects(
                      &state.pointee, first: nil, limit: split))
                } catch {
                  outcome.pointee = .failure(error)
                }
              } else {
                run.pointee.read()
              }
            }
          }
        }
      }
    }
    let progress = try outcome.get()
    guard case .reached(let token) = progress, let runFirst = run.first,
      token.start == runFirst.start, !run.spheres.isEmpty,
      run.spheres.count <= state.declared.value - state.objects.count
    else { return progress }
    // The other parser counted lines from 1 at `split`.
    let lines = token.line - runFirst.line
    let inherited = state.material
    for (offset, var sphere) in run.spheres.enumerated() {
      if offset < run.inheritingCount { sphere.materialIndex = inherited }
      state.objects.append(.sphere(sphere))
    }
    for var check in run.parser.pendingMaterialChecks {
      check.token.line += lines
      pendingMaterialChecks.append(check)
    }
    if run.sawMaterialIndex {
      state.material = run.parser.currentMaterial
    }
    splicedObjects += run.spheres.count
    var resume = run.stop
    resume.line += lines
    tokenizer.position = resume
    return .spliced
  }

  /// Plain spheres and `MaterialIndex` lines read from a point in the
  /// middle of a group, by a parser of its own, until anything else: the
  /// group's `}`, another kind of object, or an error.
  struct SphereRun {
    var parser: SceneParser
    let capacity: Int
    /// The first token read, if any.
    var first: SceneToken?
    /// Spheres rather than objects: plain values, which are copied and
    /// freed without a call per element.
    var spheres: [Sphere<Double>] = []
    /// How many spheres come before the first `MaterialIndex`, and so take
    /// the material current where the run starts.
    var inheritingCount = 0
    var sawMaterialIndex = false
    /// Where the first token not read starts.
    var stop: SceneTokenizer.Position

    init(
      bytes: SceneBytes, file: String, options: SceneOptions, from split: Int,
      capacity: Int
    ) {
      // The options decide which numbers are refused (the precision).
      parser = SceneParser(bytes: bytes, file: file, options: options)
      parser.tokenizer.position = SceneTokenizer.Position(
        index: split, line: 1, lineStart: split)
      self.capacity = capacity
      stop = parser.tokenizer.position
    }

    mutating func read() {
      spheres.reserveCapacityOnHugePages(
        Swift.min(
          capacity,
          (parser.tokenizer.bytes.count - stop.index)
            / SceneParser.minimumObjectLength))
      // A placeholder no `MaterialIndex` can give.
      parser.currentMaterial = -1
      while spheres.count < capacity {
        let token = parser.tokenizer.next()
        if first == nil { first = token }
        guard token.kind == .word,
          token.end - token.start <= SceneParser.maximumWordLength
        else { return }
        if parser.tokenizer.matches(token, "Sphere") {
          guard
            let sphere = try? parser.parseSphere(
              material: parser.currentMaterial)
          else { return }
          spheres.append(sphere)
          if !sawMaterialIndex { inheritingCount += 1 }
        } else if parser.tokenizer.matches(token, "MaterialIndex") {
          let valueToken = parser.peekStart()
          guard let value = try? parser.wholeNumber("MaterialIndex") else {
            return
          }
          parser.pendingMaterialChecks.append((value, valueToken))
          parser.currentMaterial = value
          sawMaterialIndex = true
        } else {
          return
        }
        stop = parser.tokenizer.position
      }
    }
  }
}
