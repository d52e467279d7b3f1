"""Deck text: parameter lines and substitutions that must apply."""


def parameter_xml(name, value, indent=4):
    """One `<Parameter .../>` line: bool, int, double (repr, exact), string, or an array (a list or tuple of numbers
    or of strings), by the value's Python type."""
    pad = " " * indent
    if isinstance(value, (list, tuple)):
        numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)
        items = ", ".join(repr(float(v)) if numbers else str(v) for v in value)
        return '%s<Parameter name="%s" type="Array(%s)" value="{%s}"/>\n' % (pad, name, "double" if numbers else "string",
                                                                         items)
    if isinstance(value, bool):
        return '%s<Parameter name="%s" type="bool" value="%s"/>\n' % (pad, name, "true" if value else "false")
    if isinstance(value, int):
        return '%s<Parameter name="%s" type="int" value="%d"/>\n' % (pad, name, value)
    if isinstance(value, float):
        return '%s<Parameter name="%s" type="double" value="%r"/>\n' % (pad, name, value)
    return '%s<Parameter name="%s" type="string" value="%s"/>\n' % (pad, name, value)


def parameters_xml(params, indent=4):
    """The `<Parameter .../>` lines of a dict (name -> value), in its order."""
    return "".join(parameter_xml(name, value, indent) for name, value in params.items())


def sublist_xml(name, params, indent=2):
    """A `<ParameterList name="...">` of the parameter lines of a dict."""
    pad = " " * indent
    return '%s<ParameterList name="%s">\n%s%s</ParameterList>\n' % (pad, name, parameters_xml(params, indent + 2), pad)


class DeckError(Exception):
    """A substitution that did not apply: the template changed, and the result would silently be another deck."""


def substitute(text, old, new, what="deck"):
    """text with every `old` replaced by `new`; DeckError naming `what` if `old` does not occur."""
    if old not in text:
        raise DeckError("%s: '%s' not found" % (what, old[:80]))
    return text.replace(old, new)


def torn_cylinder(radius, length, axial, circumferential, material, time_integration, output="", fracture="",
                  regions=""):
    """A clamped-free aluminium cylinder (h = 1.5 mm) loaded by an exponential pressure pulse (3.37 MPa, decay
    0.692 ms) on a patch 22.5-135 degrees round and the middle half of its length: the A319 patch's load on a
    generated cylinder. `material`, `time_integration`: dicts of those sublists' parameters; `output`,
    `fracture`: whole sublists (sublist_xml) or ""; `regions`: extra region sublists (e.g. a probe)."""
    r0, r1 = 0.9 * radius, 1.1 * radius
    return """<ParameterList name="shellfrac">
  <ParameterList name="Mesh">
    <Parameter name="Source" type="string" value="Cylinder"/>
    <ParameterList name="Cylinder">
      <Parameter name="Radius" type="double" value="%(radius)r"/>
      <Parameter name="Length" type="double" value="%(length)r"/>
      <Parameter name="Axial Elements" type="int" value="%(axial)d"/>
      <Parameter name="Circumferential Elements" type="int" value="%(circumferential)d"/>
      <Parameter name="Block Name" type="string" value="skin"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Blocks">
    <ParameterList name="skin">
      <Parameter name="Thickness" type="double" value="1.5e-3"/>
      <Parameter name="Material" type="string" value="al"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Materials">
    <ParameterList name="al">
%(material)s    </ParameterList>
  </ParameterList>
%(fracture)s  <ParameterList name="Regions">
    <ParameterList name="patch">
      <Parameter name="Shape" type="string" value="Cylinder Sector"/>
      <Parameter name="Center" type="Array(double)" value="{0, 0, 0}"/>
      <Parameter name="Axis" type="Array(double)" value="{1, 0, 0}"/>
      <Parameter name="Reference Direction" type="Array(double)" value="{0, 0, 1}"/>
      <Parameter name="Angle Range" type="Array(double)" value="{22.5, 135}"/>
      <Parameter name="Axial Range" type="Array(double)" value="{%(a0)r, %(a1)r}"/>
      <Parameter name="Radius Range" type="Array(double)" value="{%(r0)r, %(r1)r}"/>
    </ParameterList>
%(regions)s  </ParameterList>
  <ParameterList name="Loads">
    <ParameterList name="pulse">
      <Parameter name="Type" type="string" value="Pressure"/>
      <Parameter name="Elements" type="string" value="patch"/>
      <Parameter name="Function" type="string" value="Exponential"/>
      <Parameter name="Pressure" type="double" value="3.37e6"/>
      <Parameter name="Decay Time" type="double" value="6.92e-4"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Time Integration">
%(time_integration)s  </ParameterList>
%(output)s</ParameterList>
""" % dict(radius=radius, length=length, axial=axial, circumferential=circumferential,
           material=parameters_xml(material, 6), time_integration=parameters_xml(time_integration), output=output, fracture=fracture, regions=regions,
           a0=round(0.25 * length, 12), a1=round(0.75 * length, 12), r0=round(r0, 12), r1=round(r1, 12))
