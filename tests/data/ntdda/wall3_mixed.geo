<?xml version="1.0" standalone="no"?>
<!DOCTYPE DDA SYSTEM "geometry.dtd">
<Berkeley:DDA xmlns:Berkeley="http://www.tsoft.com/~bdoolin/dda">
<!-- from wall3_mixed.json by json2ntdda.py: 11 blocks, 16 joint segments -->
<Berkeley:Geometry>
<Berkeley:Edgenodedist distance="0.00254902"/>
<Jointlist>
<Joint type="1"> -1.0 -1.0 4.0 -1.0 </Joint>
<Joint type="1"> -1.0 0.0 4.0 0.0 </Joint>
<Joint type="1"> 0.0 0.5 3.0 0.5 </Joint>
<Joint type="1"> 0.0 1.0 3.0 1.0 </Joint>
<Joint type="1"> 0.0 1.5 3.0 1.5 </Joint>
<Joint type="1"> 4.0 -1.0 4.0 0.0 </Joint>
<Joint type="1"> 3.0 0.0 3.0 1.5 </Joint>
<Joint type="1"> 2.5 0.5 2.5 1.0 </Joint>
<Joint type="1"> 2.0 0.0 2.0 0.5 </Joint>
<Joint type="1"> 2.0 1.0 2.0 1.5 </Joint>
<Joint type="1"> 1.5 0.5 1.5 1.0 </Joint>
<Joint type="2"> 1.0 0.0 1.0 0.5 </Joint>
<Joint type="1"> 1.0 1.0 1.0 1.5 </Joint>
<Joint type="1"> 0.5 0.5 0.5 1.0 </Joint>
<Joint type="1"> 0.0 0.0 0.0 1.5 </Joint>
<Joint type="1"> -1.0 -1.0 -1.0 0.0 </Joint>
</Jointlist>
<Fixedpointlist><Point> -0.625 -0.075 </Point><Point> 3.625 -0.075 </Point><Point> 3.625 -0.925 </Point><Point> -0.625 -0.925 </Point></Fixedpointlist>
<Measuredpointlist><Point> 2.5 1.25 </Point></Measuredpointlist>
<Matlinelist><Line type="2"> 0.5 1.25 0.5005 1.25 </Line><Line type="2"> 1.5 1.25 1.5005 1.25 </Line><Line type="2"> 2.5 1.25 2.5005 1.25 </Line></Matlinelist>
</Berkeley:Geometry>
</Berkeley:DDA>
