#include "vtkVoxelSelection.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkVoxelSelection);

//------------------------------------------------------------------------------
const char* vtkVoxelSelection::GetModeName(int mode)
{
  switch (mode)
  {
    case POSITIVE:
      return "Positive";
    case RANGE:
      return "Range";
    case LABELS:
      return "Labels";
    default:
      return "Unknown";
  }
}

//------------------------------------------------------------------------------
void vtkVoxelSelection::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << this->GetModeAsString() << "\n";
  os << indent << "LowerThreshold: " << this->LowerThreshold << "\n";
  os << indent << "UpperThreshold: " << this->UpperThreshold << "\n";
  os << indent << "BackgroundValue: " << this->BackgroundValue << "\n";
  os << indent << "ArrayComponent: " << this->ArrayComponent
     << (this->ArrayComponent == MAGNITUDE ? " (Magnitude)\n" : "\n");
}
