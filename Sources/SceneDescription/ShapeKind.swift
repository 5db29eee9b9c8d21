import Geometry

/// A kind of object the readers learn from their caller: its name, its
/// fields, and how to make the shape from them (docs/ADDING-A-SHAPE.md).
///
/// The text format reads it as `NAME { field numbers… }`, each field once,
/// in any order; a property list as a dictionary with `type` NAME, each
/// field a string of numbers, and an optional `materialIndex`. The readers
/// check the count of each field's numbers and that each is finite; `make`
/// checks the rest and returns nil with a reason for values it refuses.
public struct ShapeKind: Sendable {
  /// The block name in the text format, the `type` in a property list.
  public var name: String
  /// Each field's name and how many numbers it takes.
  public var fields: [(name: String, count: Int)]
  /// The shape from its fields' numbers (every field given) and its
  /// material index, or the reason the values make no shape.
  public var make:
    @Sendable (_ values: [String: [Double]], _ materialIndex: Int) ->
      Result<any Hittable, ShapeError>

  public init(
    name: String, fields: [(name: String, count: Int)],
    make:
      @escaping @Sendable (_ values: [String: [Double]], _ materialIndex: Int)
      -> Result<any Hittable, ShapeError>
  ) {
    self.name = name
    self.fields = fields
    self.make = make
  }
}

/// Why a shape's values make no shape: a sentence for the scene's error
/// message ("'radius' must be positive").
public struct ShapeError: Error, Sendable {
  public var message: String

  public init(_ message: String) {
    self.message = message
  }
}
