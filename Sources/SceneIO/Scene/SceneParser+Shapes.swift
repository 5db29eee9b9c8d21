import Geometry
import SceneDescription

/// Kinds of object the readers learn from their caller
/// (`SceneOptions.shapes`, docs/ADDING-A-SHAPE.md), in the text format.
extension SceneParser {
  /// `NAME { field numbers… }` for a kind of object the caller added
  /// (`SceneOptions.shapes`): each of its fields once, in any order.
  mutating func parseShape(
    _ kind: ShapeKind, _ start: SceneToken, material: Int
  ) throws(SceneError) -> SceneObject<Double> {
    try expect(.open, "'{' after \(kind.name)")
    var values: [String: [Double]] = [:]
    while true {
      let token = try next()
      switch token.kind {
      case .close:
        let given = kind.fields.map { ($0.name, values[$0.name] != nil) }
        guard given.allSatisfy(\.1) else {
          throw missing(kind.name, given, token)
        }
        switch kind.make(values, material) {
        case .success(let shape): return .shape(Shape(shape))
        case .failure(let problem):
          throw error(at: start, "\(kind.name): \(problem.message)")
        }
      case .end, .open:
        throw unexpectedEnd(token, in: kind.name)
      case .word:
        let word = tokenizer.text(of: token)
        guard let field = kind.fields.first(where: { $0.name == word }) else {
          throw unexpected(
            token, expected: "a field of \(kind.name)",
            choices: kind.fields.map(\.name))
        }
        guard values[word] == nil else {
          throw error(at: token, "'\(word)' is given twice in \(kind.name)")
        }
        var numbers: [Double] = []
        for _ in 0..<field.count { numbers.append(try number()) }
        values[word] = numbers
      }
    }
  }
}
