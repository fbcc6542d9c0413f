<?xml version="1.0" standalone="no"?>
<!DOCTYPE DDA SYSTEM "geometry.dtd">
<!-- Written for ddaslope's tests in the DDAML form ntdda reads (no ntdda file copied): a fixed
     base, a block on it, a block cut by a diagonal joint of type 2 and pushed by a load point, and
     a line into the air that bounds nothing. Lines overshoot their corners, as drawn in ntdda. -->
<Berkeley:DDA xmlns:Berkeley="http://www.tsoft.com/~bdoolin/dda">
<Berkeley:Geometry>
   <Berkeley:Edgenodedist distance="0.001"/>
   <Jointlist>
      <Joint type="1"> -0.02 0 20.02 0 </Joint>
      <Joint type="1"> 20 -0.02 20 2.02 </Joint>
      <Joint type="1"> 20.02 2 -0.02 2 </Joint>
      <Joint type="1"> 0 2.02 0 -0.02 </Joint>
      <!-- block A: its sides end on the base's top (T-junctions) -->
      <Joint type="1"> 2 2 2 4.01 </Joint>
      <Joint type="1"> 1.99 4 6.01 4 </Joint>
      <Joint type="1"> 6 4.01 6 2 </Joint>
      <!-- block B and its diagonal joint -->
      <Joint type="1"> 8 2 8 3 </Joint>
      <Joint type="1"> 8 3 12 3 </Joint>
      <Joint type="1"> 12 3 12 2 </Joint>
      <Joint type="2"> 8 2 12 3 </Joint>
      <Joint type="1"> 14 2 15 3.5 </Joint>
   </Jointlist>
   <Fixedpointlist>
      <Point> 1 1 </Point>
      <Point> 19 1 </Point>
   </Fixedpointlist>
   <Loadpointlist>
      <Point> 11 2.4 </Point>
   </Loadpointlist>
   <Measuredpointlist>
      <Point> 4 3 </Point>
   </Measuredpointlist>
   <Matlinelist>
      <Line type="2"> 3 3 3.1 3 </Line>
   </Matlinelist>
</Berkeley:Geometry>
</Berkeley:DDA>
