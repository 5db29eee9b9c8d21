/// A type whose values can be read from one command-line token.
public protocol ExpressibleByArgument: _SendableMetatype {
  /// Nil when `argument` is not a valid value; the parser then reports it
  /// with the option's name and, for enumerations, the choices.
  init?(argument: String)

  /// How help shows this value as a default: `(default: <description>)`.
  var defaultValueDescription: String { get }

  /// The choices help lists as `(values: …)`; empty when any text goes.
  static var allValueStrings: [String] { get }

  static var defaultCompletionKind: CompletionKind { get }
}

extension ExpressibleByArgument {
  public var defaultValueDescription: String {
    "\(self)"
  }

  public static var allValueStrings: [String] {
    []
  }

  public static var defaultCompletionKind: CompletionKind {
    .default
  }
}

extension ExpressibleByArgument where Self: CaseIterable {
  public static var allValueStrings: [String] {
    allCases.map { String(describing: $0) }
  }

  public static var defaultCompletionKind: CompletionKind {
    .list(allValueStrings)
  }
}

extension ExpressibleByArgument
where Self: CaseIterable, Self: RawRepresentable, RawValue == String {
  public static var allValueStrings: [String] {
    allCases.map(\.rawValue)
  }
}

extension ExpressibleByArgument
where Self: RawRepresentable, RawValue: ExpressibleByArgument {
  /// An enumeration's default shows its raw value (`double`), not its case
  /// name as Swift spells it.
  public var defaultValueDescription: String {
    rawValue.defaultValueDescription
  }
}

extension RawRepresentable
where Self: ExpressibleByArgument, RawValue: ExpressibleByArgument {
  /// Lets `extension MyEnum: ExpressibleByArgument {}` be the whole
  /// conformance.
  public init?(argument: String) {
    guard let rawValue = RawValue(argument: argument) else { return nil }
    self.init(rawValue: rawValue)
  }
}

extension String: ExpressibleByArgument {
  public init?(argument: String) {
    self = argument
  }
}

extension Substring: ExpressibleByArgument {
  public init?(argument: String) {
    self = argument[...]
  }
}

extension Bool: ExpressibleByArgument {
  public init?(argument: String) {
    self.init(argument)
  }
}

extension Double: ExpressibleByArgument {
  public init?(argument: String) {
    self.init(argument)
  }
}

extension Float: ExpressibleByArgument {
  public init?(argument: String) {
    self.init(argument)
  }
}

extension Int: ExpressibleByArgument {}
extension Int8: ExpressibleByArgument {}
extension Int16: ExpressibleByArgument {}
extension Int32: ExpressibleByArgument {}
extension Int64: ExpressibleByArgument {}
extension UInt: ExpressibleByArgument {}
extension UInt8: ExpressibleByArgument {}
extension UInt16: ExpressibleByArgument {}
extension UInt32: ExpressibleByArgument {}
extension UInt64: ExpressibleByArgument {}

extension FixedWidthInteger where Self: ExpressibleByArgument {
  /// Decimal only, as in the real package: `0x10` is not a number here.
  public init?(argument: String) {
    self.init(argument, radix: 10)
  }
}
