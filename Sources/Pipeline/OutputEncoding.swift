import Dispatch
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport
import Course
import FastEngine

/// A render's files as bytes: each 8-bit image read a row at a time from
/// the buffers (`ImageStyle.depthRows` and the like, so no image is held
/// whole beside them), PNGs cut into pieces (`PNGEncoder.Pieces`), and
/// every piece of every file compressed on whichever thread is free.
///
/// Encoding the three files of a course render one per thread took as long
/// as the render (the third file waited for a thread); in pieces the
/// threads share the work evenly.
enum OutputEncoding {
  /// The bytes of each file, in the order of `files`.
  static func encode<S: RayScalar>(
    _ buffers: RenderBuffers<S>, files: [OutputFile], style: ImageStyle,
    depthRange: ClosedRange<Double>?, png: PNGOptions, threads: Int = 1
  ) -> [[UInt8]] {
    let jobs = files.map { file in
      Job(
        file, buffers, style: style, depthRange: depthRange, png: png,
        threads: threads)
    }
    // Every job's parts, in file order.
    let parts = jobs.indices.flatMap { job in
      (0..<jobs[job].partCount).map { (job: job, part: $0) }
    }
    let results = Slots<Result>(count: parts.count)
    DispatchQueue.concurrentPerform(iterations: parts.count) { index in
      let (job, part) = parts[index]
      results.store(jobs[job].encode(part: part), at: index)
    }
    var next = 0
    return jobs.map { job in
      let range = next..<(next + job.partCount)
      next = range.upperBound
      return job.assemble(range.map { results.value(at: $0) })
    }
  }

  /// What one part of a job gives.
  enum Result {
    case piece(PNGEncoder.Pieces.Compressed)
    case whole([UInt8])
  }

  /// One file: a PNG in pieces, or another format in one part.
  enum Job: Sendable {
    case png(PNGEncoder.Pieces)
    case whole(@Sendable () -> [UInt8])

    init<S: RayScalar>(
      _ file: OutputFile, _ buffers: RenderBuffers<S>, style: ImageStyle,
      depthRange: ClosedRange<Double>?, png: PNGOptions, threads: Int
    ) {
      guard file.format.isEightBit else {
        let (kind, format) = (file.kind, file.format)
        // One part, converted by up to `threads` threads itself (PFM).
        self = .whole {
          if format == .pfm, kind != .depth,
            let bytes = Self.encodePFMInPlace(kind, buffers, threads: threads)
          {
            return bytes
          }
          return Self.encodeRaw(
            RenderJob.rawImage(kind, buffers), format, threads: threads)
        }
        return
      }
      let rows =
        file.kind == .depth
        ? style.depthRows(buffers, range: depthRange)
        : file.kind == .normals
          ? style.normalRows(buffers) : style.colorRows(buffers)
      if file.format == .png {
        self = .png(PNGEncoder.Pieces(rows, options: png))
      } else {
        self = .whole { PPMEncoder.encode(rows.image) }
      }
    }

    var partCount: Int {
      switch self {
      case .png(let pieces): pieces.count
      case .whole: 1
      }
    }

    func encode(part: Int) -> Result {
      switch self {
      case .png(let pieces): .piece(pieces.compress(part))
      case .whole(let encode): .whole(encode())
      }
    }

    func assemble(_ results: [Result]) -> [UInt8] {
      switch self {
      case .png(let pieces):
        return pieces.assemble(
          results.map {
            guard case .piece(let piece) = $0 else {
              preconditionFailure("a PNG job's part is a piece")
            }
            return piece
          })
      case .whole:
        guard results.count == 1, case .whole(let bytes) = results[0] else {
          preconditionFailure("a whole job has one part")
        }
        return bytes
      }
    }

    /// The PFM file of the normals or colours read where they are, three
    /// values a pixel, without `RenderJob.rawImage`'s flat copy (47 MiB in
    /// Double at 1920×1080, at the peak of a large mesh's render); nil
    /// where a vector is not three values in a row.
    private static func encodePFMInPlace<S: RayScalar>(
      _ kind: RenderOutputs, _ buffers: RenderBuffers<S>, threads: Int
    ) -> [UInt8]? {
      guard MemoryLayout<Vector3<S>>.stride == 3 * MemoryLayout<S>.stride
      else { return nil }
      let vectors = kind == .normals ? buffers.normals : buffers.color
      return vectors.withUnsafeBufferPointer { vectors in
        vectors.withMemoryRebound(to: S.self) { values in
          PFMEncoder.encode(
            width: buffers.width, height: buffers.height, channels: 3,
            values: UnsafeBufferPointer(
              rebasing: values[..<(3 * vectors.count)]), threads: threads)
        }
      }
    }

    /// PFM is 32-bit by definition; NPY keeps the render's precision.
    private static func encodeRaw<S: RayScalar>(
      _ image: RawImage<S>, _ format: ImageFormat, threads: Int
    ) -> [UInt8] {
      if format == .pfm {
        return PFMEncoder.encode(converting: image, threads: threads)
      }
      return NPYEncoder.encode(image)
    }
  }
}

/// One slot per part of some work, each written by exactly one thread:
/// fixed storage, so that no write touches shared array bookkeeping.
final class Slots<Value>: @unchecked Sendable {
  private let slots: UnsafeMutableBufferPointer<Value?>

  init(count: Int) {
    slots = .allocate(capacity: count)
    slots.initialize(repeating: nil)
  }

  deinit {
    slots.deinitialize()
    slots.deallocate()
  }

  func store(_ value: Value, at index: Int) {
    slots[index] = value
  }

  /// The value stored at `index`, which must have been stored.
  func value(at index: Int) -> Value {
    guard let value = slots[index] else {
      preconditionFailure("slot \(index) was never stored")
    }
    return value
  }
}
