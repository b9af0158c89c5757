"""Every property the plugin XML declares reaches the panel, properly named and documented.

Usage: pvbatch TestPluginProperties.py /path/to/VoxelBRep.so /path/to/VoxelBRep.xml

Walks the XML (independently of the server manager) and, for every proxy, creates it through
paraview.simple and checks each declared property:
- it exists on the proxy, under its XML name and under the Python name its label gives;
- its label is a proper one (no auto-generated "Flat Images As2 D") and it has a
  Documentation;
- it is of a kind the Qt panel shows (no IdTypeVectorProperty, which has no widget) and is
  not hidden (panel_visibility="never");
- it belongs to exactly one PropertyGroup, the "Advanced" group holding exactly the
  panel_visibility="advanced" properties.
Also: every InputArrayDomain names its attribute type (else the help page shows "field array
()"). The enumeration names against the VTK API and the progress texts are checked by
Filters/Testing/Python/TestPluginNames.py (the VTK classes are wrapped there).
"""

import re
import sys

from paraview.simple import *  # noqa: F401,F403
from pvtest import expect, finish
from voxelbrep_testing import plugin_proxies

plugin, xml_path = sys.argv[1], sys.argv[2]
LoadPlugin(plugin, remote=False, ns=globals())

PROPERTY_TAGS = {"IntVectorProperty", "DoubleVectorProperty", "StringVectorProperty",
                 "IdTypeVectorProperty", "InputProperty", "ProxyProperty"}
PANEL_KINDS = PROPERTY_TAGS - {"IdTypeVectorProperty"}


def python_name(label):
    """How paraview.simple names a property: its label without spaces and symbols."""
    return re.sub(r"[^A-Za-z0-9_]", "", label)


def create(proxy_xml, phantom, polyhedrizer):
    label = proxy_xml.get("label")
    factory = globals()[python_name(label)]
    if proxy_xml.find("InputProperty") is None:
        return factory()
    source = polyhedrizer if proxy_xml.get("name") == "StandardPlaneReversion" else phantom
    SetActiveSource(source)
    return factory(Input=source)


def check_property(proxy_name, proxy, prop):
    name, kind = prop.get("name"), prop.tag
    tag = "%s.%s" % (proxy_name, name)
    sm = proxy.SMProxy.GetProperty(name)
    expect(tag + ": exists on the proxy", sm is not None, True)
    # The label the panel shows: the XML's, else the one ParaView makes from the name.
    label = prop.get("label") or (sm.GetXMLLabel() if sm is not None else "") or ""
    if sm is not None:
        expect(tag + ": proxy label", sm.GetXMLLabel(), label)
    # An auto-generated label of a name with digits reads "Flat Images As2 D".
    expect(tag + ": label %r is a proper one" % label,
           re.search(r"[a-z]\d|\d [A-Z]\b", label) is None and label != "", True)
    expect(tag + ": Python name %s" % python_name(label),
           python_name(label) in proxy.ListProperties() or kind == "InputProperty", True)
    doc = prop.find("Documentation")
    expect(tag + ": documented", doc is not None and len((doc.text or "").split()) >= 4, True)
    expect(tag + ": a kind the panel shows (%s)" % kind, kind in PANEL_KINDS, True)
    expect(tag + ": not hidden from the panel", prop.get("panel_visibility") != "never", True)
    for domain in prop.iter("InputArrayDomain"):
        expect(tag + ": InputArrayDomain names its attribute type",
               domain.get("attribute_type") is not None, True)


def check_groups(proxy_name, proxy_xml, properties):
    grouped = {}
    for group in proxy_xml.findall("PropertyGroup"):
        for member in group.findall("Property"):
            grouped.setdefault(member.get("name"), []).append(group.get("label"))
    panel = [p for p in properties if p.tag != "InputProperty"]
    if len(panel) < 2:
        return  # a single property needs no group
    for prop in panel:
        name = prop.get("name")
        groups = grouped.get(name, [])
        expect("%s.%s: in exactly one property group" % (proxy_name, name), len(groups), 1)
        advanced = prop.get("panel_visibility") == "advanced"
        expect("%s.%s: in the Advanced group iff advanced" % (proxy_name, name),
               groups == ["Advanced"], advanced)
    declared = {p.get("name") for p in properties}
    for name in grouped:
        expect("%s: group member %s is a declared property" % (proxy_name, name),
               name in declared, True)


phantom = VoxelPhantom(Dimensions=[16, 16, 16])
phantom.UpdatePipeline()  # array domains need the data information
SetActiveSource(phantom)
polyhedrizer = StandardPlanePolyhedrizer(Input=phantom)
polyhedrizer.UpdatePipeline()
proxies = plugin_proxies(xml_path)  # as ParaView reads them: bases merged in
expect("the XML declares the seven proxies", len(proxies), 7)
for proxy_xml in proxies:
    proxy_name = proxy_xml.get("name")
    proxy = create(proxy_xml, phantom, polyhedrizer)
    properties = [p for p in proxy_xml if p.tag in PROPERTY_TAGS]
    for prop in properties:
        check_property(proxy_name, proxy, prop)
    check_groups(proxy_name, proxy_xml, properties)
    doc = proxy_xml.find("Documentation")
    expect(proxy_name + ": documented", doc is not None and doc.get("short_help") is not None, True)
finish()
