/**
 * @class   vtkVoxelSelection
 * @brief   which voxels of an image the VoxelBRep filters take as the object
 *
 * Every VoxelBRep filter selects voxels the same way, with the same properties, kept here
 * once (the way vtkDiscreteFlyingEdges3D keeps its values in a vtkContourValues):
 * - Mode: POSITIVE (every voxel whose value is > 0, the default), RANGE (LowerThreshold <=
 *   value <= UpperThreshold, inclusive, compared exactly with the values of the array's
 *   type) or LABELS (every distinct value other than BackgroundValue, each on its own).
 * - LowerThreshold, UpperThreshold: the range of RANGE mode, default [1, VTK_DOUBLE_MAX].
 *   (The ParaView plugin's defaults follow the selected array's range [min, max]: the lower
 *   threshold at its middle, as for ParaView's Contour, the upper at max.)
 * - BackgroundValue: the value that is not a label in LABELS mode, default 0. A background
 *   the array's type cannot hold exactly means that every value is a label.
 * - ArrayComponent: the component of the input array, 0 to N - 1 for N components, or
 *   MAGNITUDE (-1; N means the same, as in ParaView's component selectors and vtkThreshold)
 *   for the Euclidean norm of each tuple, computed in double. Default 0.
 *
 * A filter holds one vtkVoxelSelection and forwards the properties through
 * vtkVoxelSelectionMacro(), so that its own Set/Get methods (what Python scripts and the
 * ParaView XML call) and its modification time follow the selection's.
 *
 * @sa vtkEVMBoundaryFilter vtkCUDBConnectivity vtkStandardPlanePolyhedrizer
 */
#ifndef vtkVoxelSelection_h
#define vtkVoxelSelection_h

#include "VoxelBRepFiltersModule.h" // for export macro
#include "vtkNew.h"                 // for vtkVoxelSelectionMacro
#include "vtkObject.h"

class VOXELBREPFILTERS_EXPORT vtkVoxelSelection : public vtkObject
{
public:
  static vtkVoxelSelection* New();
  vtkTypeMacro(vtkVoxelSelection, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Modes
  {
    POSITIVE = 0, ///< every voxel whose value is > 0
    RANGE = 1,    ///< LowerThreshold <= value <= UpperThreshold
    LABELS = 2    ///< every distinct value other than BackgroundValue, each on its own
  };
  enum Components
  {
    MAGNITUDE = -1 ///< ArrayComponent value: the Euclidean norm of each tuple
  };

  ///@{
  /// How voxels are selected (see the class comment). The default is POSITIVE.
  vtkSetClampMacro(Mode, int, POSITIVE, LABELS);
  vtkGetMacro(Mode, int);
  /// "Positive", "Range" or "Labels" (the names of the ParaView XML's enumeration).
  static const char* GetModeName(int mode);
  const char* GetModeAsString() { return GetModeName(this->Mode); }
  ///@}

  ///@{
  /// The inclusive range of RANGE mode. The default is [1, VTK_DOUBLE_MAX].
  vtkSetMacro(LowerThreshold, double);
  vtkGetMacro(LowerThreshold, double);
  vtkSetMacro(UpperThreshold, double);
  vtkGetMacro(UpperThreshold, double);
  ///@}

  ///@{
  /// The value that is not a label in LABELS mode. The default is 0.
  vtkSetMacro(BackgroundValue, double);
  vtkGetMacro(BackgroundValue, double);
  ///@}

  ///@{
  /// The component of the input array, or MAGNITUDE (-1). The default is 0.
  vtkSetClampMacro(ArrayComponent, int, MAGNITUDE, VTK_INT_MAX);
  vtkGetMacro(ArrayComponent, int);
  ///@}

protected:
  vtkVoxelSelection() = default;
  ~vtkVoxelSelection() override = default;

  int Mode = POSITIVE;
  double LowerThreshold = 1.0;
  double UpperThreshold = VTK_DOUBLE_MAX;
  double BackgroundValue = 0.0;
  int ArrayComponent = 0;

private:
  vtkVoxelSelection(const vtkVoxelSelection&) = delete;
  void operator=(const vtkVoxelSelection&) = delete;
};

/**
 * The selection properties of a filter, forwarded to its vtkVoxelSelection (placed in the
 * public section of the filter's class): SelectionMode (SetSelectionModeToPositive, ...ToRange,
 * ...ToLabels, GetSelectionModeAsString), LowerThreshold, UpperThreshold, BackgroundValue and
 * ArrayComponent (SetArrayComponentToMagnitude), with the constants POSITIVE, RANGE, LABELS
 * and MAGNITUDE; GetSelection() gives the object itself, and GetMTime() includes its
 * modification time. The member it forwards to, `Selection`, is protected.
 */
#define vtkVoxelSelectionMacro()                                                                   \
  enum SelectionModes                                                                              \
  {                                                                                                \
    POSITIVE = vtkVoxelSelection::POSITIVE,                                                        \
    RANGE = vtkVoxelSelection::RANGE,                                                              \
    LABELS = vtkVoxelSelection::LABELS                                                             \
  };                                                                                               \
  enum ArrayComponents                                                                             \
  {                                                                                                \
    MAGNITUDE = vtkVoxelSelection::MAGNITUDE                                                       \
  };                                                                                               \
  void SetSelectionMode(int mode)                                                                  \
  {                                                                                                \
    this->Selection->SetMode(mode);                                                                \
  }                                                                                                \
  int GetSelectionMode()                                                                           \
  {                                                                                                \
    return this->Selection->GetMode();                                                             \
  }                                                                                                \
  void SetSelectionModeToPositive()                                                                \
  {                                                                                                \
    this->SetSelectionMode(POSITIVE);                                                              \
  }                                                                                                \
  void SetSelectionModeToRange()                                                                   \
  {                                                                                                \
    this->SetSelectionMode(RANGE);                                                                 \
  }                                                                                                \
  void SetSelectionModeToLabels()                                                                  \
  {                                                                                                \
    this->SetSelectionMode(LABELS);                                                                \
  }                                                                                                \
  const char* GetSelectionModeAsString()                                                           \
  {                                                                                                \
    return this->Selection->GetModeAsString();                                                     \
  }                                                                                                \
  void SetLowerThreshold(double value)                                                             \
  {                                                                                                \
    this->Selection->SetLowerThreshold(value);                                                     \
  }                                                                                                \
  double GetLowerThreshold()                                                                       \
  {                                                                                                \
    return this->Selection->GetLowerThreshold();                                                   \
  }                                                                                                \
  void SetUpperThreshold(double value)                                                             \
  {                                                                                                \
    this->Selection->SetUpperThreshold(value);                                                     \
  }                                                                                                \
  double GetUpperThreshold()                                                                       \
  {                                                                                                \
    return this->Selection->GetUpperThreshold();                                                   \
  }                                                                                                \
  void SetBackgroundValue(double value)                                                            \
  {                                                                                                \
    this->Selection->SetBackgroundValue(value);                                                    \
  }                                                                                                \
  double GetBackgroundValue()                                                                      \
  {                                                                                                \
    return this->Selection->GetBackgroundValue();                                                  \
  }                                                                                                \
  void SetArrayComponent(int component)                                                            \
  {                                                                                                \
    this->Selection->SetArrayComponent(component);                                                 \
  }                                                                                                \
  int GetArrayComponent()                                                                          \
  {                                                                                                \
    return this->Selection->GetArrayComponent();                                                   \
  }                                                                                                \
  void SetArrayComponentToMagnitude()                                                              \
  {                                                                                                \
    this->SetArrayComponent(MAGNITUDE);                                                            \
  }                                                                                                \
  vtkVoxelSelection* GetSelection()                                                                \
  {                                                                                                \
    return this->Selection;                                                                        \
  }                                                                                                \
  vtkMTimeType GetMTime() override                                                                 \
  {                                                                                                \
    const vtkMTimeType own = this->Superclass::GetMTime();                                         \
    const vtkMTimeType selection = this->Selection->GetMTime();                                    \
    return own > selection ? own : selection;                                                      \
  }                                                                                                \
                                                                                                   \
protected:                                                                                         \
  vtkNew<vtkVoxelSelection> Selection;                                                             \
                                                                                                   \
public:

#endif
