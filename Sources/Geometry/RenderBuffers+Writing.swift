extension RenderBuffers {
  /// The buffers `outputs` asks for, written in place by `body`, handed
  /// batches of rows on `threads` threads (`RowBatches`), which must store
  /// every pixel of its rows: not zeroed first, and no lock, rows being
  /// disjoint (docs/PERFORMANCE.md, "Many cores").
  package static func written(
    width: Int, height: Int, outputs: RenderOutputs, threads: Int,
    progress: (@Sendable (Int) -> Void)?,
    _ body: @Sendable (Range<Int>, Pixels) -> Void
  ) -> RenderBuffers {
    let pixels = width * height
    func count(_ o: RenderOutputs) -> Int { outputs.contains(o) ? pixels : 0 }
    var (normals, color): ([Vector3<Scalar>], [RGB<Scalar>]) = ([], [])
    let depth = [Scalar](unsafeUninitializedCapacity: count(.depth)) {
      depth, depthCount in
      normals = .init(unsafeUninitializedCapacity: count(.normals)) {
        normals, normalsCount in
        color = .init(unsafeUninitializedCapacity: count(.shaded)) {
          color, colorCount in
          let targets = Pixels(
            depth: .init(rebasing: depth[..<count(.depth)]),
            normals: .init(rebasing: normals[..<count(.normals)]),
            color: .init(rebasing: color[..<count(.shaded)]))
          RowBatches.forEach(rows: height, threads: threads, progress: progress)
          { rows in body(rows, targets) }
          (depthCount, normalsCount, colorCount) = (
            count(.depth), count(.normals), count(.shaded)
          )
        }
      }
    }
    return RenderBuffers(
      width: width, height: height, depth: depth, normals: normals,
      color: color)
  }

  /// Where a render's threads store its pixels, each once (`written`),
  /// index i being pixel (i mod width, i div width); a buffer not asked
  /// for is empty, and nothing is stored in it.
  /// Inlined `store` (the type `@usableFromInline` for it): as a generic it
  /// took a runtime lock per pixel (docs/PERFORMANCE.md, "Many cores").
  @usableFromInline
  package struct Pixels: @unchecked Sendable {
    @usableFromInline let depth: UnsafeMutableBufferPointer<Scalar>
    @usableFromInline let normals: UnsafeMutableBufferPointer<Vector3<Scalar>>
    @usableFromInline let color: UnsafeMutableBufferPointer<RGB<Scalar>>

    @inlinable
    package func store(
      _ pixel: (depth: Scalar, normal: Vector3<Scalar>, color: RGB<Scalar>),
      at i: Int
    ) {
      if !depth.isEmpty { depth[i] = pixel.depth }
      if !normals.isEmpty { normals[i] = pixel.normal }
      if !color.isEmpty { color[i] = pixel.color }
    }
  }
}
