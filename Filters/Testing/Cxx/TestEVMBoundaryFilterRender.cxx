// Regression image: the boundary of the phantom (nested shells, handle, pierced plate, frame,
// boxes in non-manifold contact), triangulated faces coloured by label.
#include "vtkEVMBoundaryFilter.h"
#include "vtkVoxelPhantomSource.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"

int TestEVMBoundaryFilterRender(int argc, char* argv[])
{
  vtkNew<vtkVoxelPhantomSource> phantom;
  phantom->SetDimensions(48, 48, 48);

  vtkNew<vtkEVMBoundaryFilter> faces;
  faces->SetInputConnection(phantom->GetOutputPort());
  faces->SetSelectionModeToLabels();
  vtkNew<vtkPolyDataMapper> faceMapper;
  faceMapper->SetInputConnection(faces->GetOutputPort());
  faceMapper->SetScalarModeToUseCellFieldData();
  faceMapper->SelectColorArray("Label");
  faceMapper->SetScalarRange(1, 5);
  faceMapper->SetColorModeToMapScalars();
  vtkNew<vtkActor> faceActor;
  faceActor->SetMapper(faceMapper);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(faceActor);
  renderer->SetBackground(1, 1, 1);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(300, 300);
  window->AddRenderer(renderer);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Elevation(35);
  renderer->GetActiveCamera()->Azimuth(30);
  renderer->ResetCamera();
  window->Render();

  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  return !result;
}
