"""The plugin XML's names against the VTK API: every enumeration entry's text is the suffix
of the VTK setter (SetXToText sets its value) and what GetXAsString returns for that value,
and each filter's progress text is its proxy's label (ParaView's progress bar shows it).

Usage: python TestPluginNames.py /path/to/Plugin/VoxelBRep.xml
"""

import sys
import voxelbrep
from voxelbrep_testing import Checker, plugin_proxies

check = Checker("TestPluginNames")

for proxy in plugin_proxies(sys.argv[1]):
    cls = proxy.get("class")
    obj = getattr(voxelbrep, cls)()
    check.equal(cls + ": progress text", obj.GetProgressText(), proxy.get("label"))
    for prop in proxy:
        if prop.find("EnumerationDomain") is None:
            continue
        base = prop.get("command")[3:]
        for entry in prop.iter("Entry"):
            text, value = entry.get("text"), int(entry.get("value"))
            setter = getattr(obj, "Set%sTo%s" % (base, text), None)
            check.true("%s: Set%sTo%s exists" % (cls, base, text), setter is not None)
            if setter is None:
                continue
            setter()
            check.equal("%s: Set%sTo%s sets %d" % (cls, base, text, value),
                        getattr(obj, "Get" + base)(), value)
            check.equal("%s: Get%sAsString() of %d" % (cls, base, value),
                        getattr(obj, "Get%sAsString" % base)(), text)
check.finish()
