import CZlib
import Geometry
import SceneDescription
import PlatformSupport

extension PNGEncoder {
  /// A PNG's image data cut into pieces of whole rows that compress
  /// independently, on any threads, and are then joined into the file.
  ///
  /// A zlib stream is a two-byte header, raw deflate data and the Adler-32
  /// of the uncompressed bytes. Each piece is its own raw deflate stream
  /// (no dictionary: a piece's matches reach back only within it), ended
  /// by a sync flush (an empty stored block, which leaves the stream at a
  /// byte boundary and not final), the last piece by the final block; so
  /// the pieces' bytes laid end to end are one valid deflate stream
  /// (RFC 1951 §3.2.3: blocks follow one another, each starting where the
  /// last ended). The checksum is the pieces' checksums combined
  /// (`adler32_combine`). The same construction as parallel gzip's.
  ///
  /// A piece cannot match across its first row; with pieces of about
  /// 256 KiB the course scene's images came out 0.4–1.6 % smaller all the
  /// same, each piece's Huffman codes fitting its own rows
  /// (docs/PERFORMANCE.md, "Writing images").
  package struct Pieces: Sendable {
    package let rows: PixelRows
    package let options: PNGOptions
    /// Rows per piece; the last piece may have fewer.
    package let rowsPerPiece: Int

    /// About this many filtered bytes a piece: large enough that the lost
    /// matches at its start do not matter, small enough that an image of
    /// a few hundred rows gives both threads several pieces.
    package static let targetPieceBytes = 256 * 1024

    /// About this many filtered bytes go to zlib at a time (whole rows, at
    /// least one).
    static let batchBytes = 32 * 1024

    package init(
      _ rows: PixelRows, options: PNGOptions,
      rowsPerPiece: Int? = nil
    ) {
      self.rows = rows
      self.options = options
      self.rowsPerPiece = Swift.max(
        1, rowsPerPiece ?? Self.targetPieceBytes / (rows.stride + 1))
    }

    /// At least one, so that an image without rows still gets a stream.
    package var count: Int {
      Swift.max(1, (rows.height + rowsPerPiece - 1) / rowsPerPiece)
    }

    /// One piece's deflate bytes, and the Adler-32 and length of the
    /// filtered bytes it holds.
    package struct Compressed: Sendable {
      var bytes: [UInt8]
      var adler: UInt
      var length: Int
    }

    /// Filters and compresses the rows of piece `index`; the row before
    /// its first is read again for the filters that look up.
    package func compress(_ index: Int) -> Compressed {
      precondition(index >= 0 && index < count)
      let first = index * rowsPerPiece
      let end = Swift.min(rows.height, first + rowsPerPiece)
      let stride = rows.stride
      let isLast = index == count - 1
      let deflater = Deflater(level: options.compressionLevel)
      var adler = CZlib.adler32(0, nil, 0)
      // Filtered rows go to zlib (and the checksum) in batches of about
      // `batchBytes`: the course scene's three PNGs 2–3 % faster to write
      // than a call per row.
      let batchRows = Swift.max(1, Self.batchBytes / (stride + 1))
      // Two raw rows (current and previous, swapped each row), the
      // adaptive filter's scratch, a batch of filtered rows with their
      // type bytes.
      var buffers = [UInt8](
        repeating: 0, count: 3 * stride + batchRows * (stride + 1))
      buffers.withUnsafeMutableBufferPointer { buffers in
        var current = UnsafeMutableBufferPointer(rebasing: buffers[0..<stride])
        var previous = UnsafeMutableBufferPointer(
          rebasing: buffers[stride..<(2 * stride)])
        let scratch = UnsafeMutableBufferPointer(
          rebasing: buffers[(2 * stride)..<(3 * stride)])
        let batch = UnsafeMutableBufferPointer(
          rebasing: buffers[(3 * stride)...])
        var batched = 0
        if first > 0 && first < end {
          rows.fill(row: first - 1, into: previous)
        }
        for row in first..<end {
          rows.fill(row: row, into: current)
          let start = batched * (stride + 1)
          filterRow(
            UnsafeBufferPointer(current),
            row > 0 ? UnsafeBufferPointer(previous) : nil, options.filter,
            into: UnsafeMutableBufferPointer(
              rebasing: batch[start..<(start + stride + 1)]),
            scratch: scratch)
          batched += 1
          if batched == batchRows || row == end - 1 {
            let filtered = UnsafeBufferPointer(
              rebasing: batch[0..<(batched * (stride + 1))])
            adler = CZlib.adler32(
              adler, filtered.baseAddress, uInt(filtered.count))
            deflater.add(
              filtered,
              ending: row == end - 1 ? (isLast ? .last : .piece) : nil)
            batched = 0
          }
          swap(&current, &previous)
        }
        if first >= end {
          deflater.add(UnsafeBufferPointer(start: nil, count: 0), ending: .last)
        }
      }
      return Compressed(
        bytes: deflater.finish(), adler: UInt(adler),
        length: (end - first) * (stride + 1))
    }

    /// The PNG file: signature, header, the pieces (in order) as one IDAT,
    /// end.
    package func assemble(_ pieces: [Compressed]) -> [UInt8] {
      precondition(pieces.count == count)
      var header: [UInt8] = []
      header.appendBigEndian(UInt32(rows.width))
      header.appendBigEndian(UInt32(rows.height))
      // Bit depth 8, colour type 2 (RGB), deflate, adaptive filtering, no
      // interlace.
      header += [8, 2, 0, 0, 0]
      var data = Self.zlibHeader(level: options.compressionLevel)
      data.reserveCapacity(pieces.reduce(6) { $0 + $1.bytes.count })
      var adler = CZlib.adler32(0, nil, 0)
      for piece in pieces {
        data += piece.bytes
        adler = adler32_combine(adler, uLong(piece.adler), .init(piece.length))
      }
      data.appendBigEndian(UInt32(adler))
      var bytes = signature
      bytes.reserveCapacity(data.count + 64)
      appendChunk("IHDR", header, to: &bytes)
      appendChunk("IDAT", data, to: &bytes)
      appendChunk("IEND", [], to: &bytes)
      return bytes
    }

    /// A zlib header for deflate with a 32 KiB window, its level field as
    /// zlib writes it (0 fastest … 3 smallest; informative only) and its
    /// check bits making the 16-bit value a multiple of 31 (RFC 1950).
    static func zlibHeader(level: Int32) -> [UInt8] {
      let method: UInt8 = 0x78
      let levelField: UInt8 =
        switch level {
        case ..<0: 2  // zlib's default, 6
        case 0, 1: 0
        case 2..<6: 1
        case 6: 2
        default: 3
        }
      var flags = levelField << 6
      let remainder = (UInt16(method) << 8 | UInt16(flags)) % 31
      if remainder != 0 { flags += UInt8(31 - remainder) }
      return [method, flags]
    }
  }
}

/// One raw deflate stream (zlib's `deflate` with no header or checksum),
/// its output gathered into an array.
final class Deflater {
  enum Ending {
    /// A sync flush: byte-aligned, not final; another stream may follow.
    case piece
    /// The final block.
    case last
  }

  private var stream = z_stream()
  private var output: [UInt8] = []

  init(level: Int32) {
    let status = deflateInit2_(
      &stream, level, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY, zlibVersion(),
      Int32(MemoryLayout<z_stream>.size))
    // Valid arguments: zlib fails here only without memory.
    precondition(status == Z_OK, "zlib deflateInit2 failed with \(status)")
  }

  deinit { deflateEnd(&stream) }

  /// Compresses `input`, then flushes as `ending` says (nil: not yet).
  func add(_ input: UnsafeBufferPointer<UInt8>, ending: Ending?) {
    let flush: Int32 =
      switch ending {
      case nil: Z_NO_FLUSH
      case .piece?: Z_SYNC_FLUSH
      case .last?: Z_FINISH
      }
    stream.next_in = UnsafeMutablePointer(mutating: input.baseAddress)
    stream.avail_in = uInt(input.count)
    withUnsafeTemporaryAllocation(of: UInt8.self, capacity: 1 << 15) { chunk in
      while true {
        stream.next_out = chunk.baseAddress
        stream.avail_out = uInt(chunk.count)
        let status = deflate(&stream, flush)
        precondition(
          status == Z_OK || status == Z_STREAM_END || status == Z_BUF_ERROR,
          "zlib deflate failed with \(status)")
        output.append(
          contentsOf: chunk[0..<(chunk.count - Int(stream.avail_out))])
        // Done when zlib left room in the output (all input taken, the
        // flush complete) or ended the stream.
        if status == Z_STREAM_END || (stream.avail_out != 0 && ending != .last)
        {
          break
        }
      }
    }
  }

  /// The bytes written.
  func finish() -> [UInt8] {
    output
  }
}
