extension RenderBuffers {
  /// The buffers `outputs` asks for at `width` × `height`, written in place
  /// by `body`, which is handed batches of rows on `threads` threads
  /// (`RowBatches`) and must write every pixel of its rows to every buffer
  /// of `Pixels` that is not empty.
  ///
  /// Each buffer is allocated once and not zeroed, and each pixel goes
  /// straight to its place: rows are disjoint memory, so threads take no
  /// lock. Zeroing the buffers and then copying each row in under a lock
  /// had been two passes over the image on one thread (35 MB at 800², three
  /// outputs), and kept the course engine from scaling past 8 cores.
  package static func written(
    width: Int, height: Int, outputs: RenderOutputs, threads: Int,
    progress: (@Sendable (Int) -> Void)?,
    _ body: @Sendable (Range<Int>, Pixels) -> Void
  ) -> RenderBuffers {
    func count(_ output: RenderOutputs) -> Int {
      outputs.contains(output) ? width * height : 0
    }
    var normals: [Vector3<Scalar>] = []
    var color: [RGB<Scalar>] = []
    let depth = [Scalar](unsafeUninitializedCapacity: count(.depth)) {
      depth, depthCount in
      normals = .init(unsafeUninitializedCapacity: count(.normals)) {
        normals, normalsCount in
        color = .init(unsafeUninitializedCapacity: count(.shaded)) {
          color, colorCount in
          let pixels = Pixels(
            depth: .init(rebasing: depth[..<count(.depth)]),
            normals: .init(rebasing: normals[..<count(.normals)]),
            color: .init(rebasing: color[..<count(.shaded)]))
          RowBatches.forEach(rows: height, threads: threads, progress: progress)
          { rows in body(rows, pixels) }
          colorCount = count(.shaded)
        }
        normalsCount = count(.normals)
      }
      depthCount = count(.depth)
    }
    return RenderBuffers(
      width: width, height: height, depth: depth, normals: normals,
      color: color)
  }

  /// Where a render's threads write its pixels, row by row, each pixel
  /// once (`written`); a buffer not asked for is empty.
  package struct Pixels: @unchecked Sendable {
    package let depth: UnsafeMutableBufferPointer<Scalar>
    package let normals: UnsafeMutableBufferPointer<Vector3<Scalar>>
    package let color: UnsafeMutableBufferPointer<RGB<Scalar>>

    /// Stores `pixel`'s values in the buffers asked for.
    package func store(
      _ pixel: (depth: Scalar, normal: Vector3<Scalar>, color: RGB<Scalar>),
      at index: Int
    ) {
      if !depth.isEmpty { depth[index] = pixel.depth }
      if !normals.isEmpty { normals[index] = pixel.normal }
      if !color.isEmpty { color[index] = pixel.color }
    }
  }
}
